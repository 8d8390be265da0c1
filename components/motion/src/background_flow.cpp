#include "background_flow.hpp"

#include <algorithm>
#include <cmath>

#include <opencv2/core.hpp>

namespace uavmot::motion {

std::vector<double> BackgroundFlow::basis(const cv::Point2f& p) const {
  // Coordinates scaled to [-1, 1] keep the normal equations well conditioned.
  const double x = 2.0 * p.x / std::max(1, size_.width - 1) - 1.0;
  const double y = 2.0 * p.y / std::max(1, size_.height - 1) - 1.0;
  std::vector<double> b;
  for (int total = 0; total <= degree_; ++total) {
    for (int i = total; i >= 0; --i) b.push_back(std::pow(x, i) * std::pow(y, total - i));
  }
  return b;
}

void BackgroundFlow::fit(const std::vector<cv::Point2f>& positions, const std::vector<cv::Vec2d>& velocities) {
  cx_.clear();
  cy_.clear();
  if (degree_ <= 0) return;
  const int terms = (degree_ + 1) * (degree_ + 2) / 2;
  const int n = static_cast<int>(positions.size());
  if (n < 3 * terms) return;
  cv::Mat a(n, terms, CV_64F);
  for (int i = 0; i < n; ++i) {
    const auto b = basis(positions[static_cast<size_t>(i)]);
    std::copy(b.begin(), b.end(), a.ptr<double>(i));
  }
  cv::Mat coef_x = cv::Mat::zeros(terms, 1, CV_64F), coef_y = cv::Mat::zeros(terms, 1, CV_64F);
  std::vector<double> residual(static_cast<size_t>(n)), weight(static_cast<size_t>(n));
  for (int iteration = 0; iteration < 6; ++iteration) {
    for (int i = 0; i < n; ++i) {
      const double fx = a.row(i).dot(coef_x.t()), fy = a.row(i).dot(coef_y.t());
      residual[static_cast<size_t>(i)] =
          std::hypot(velocities[static_cast<size_t>(i)][0] - fx, velocities[static_cast<size_t>(i)][1] - fy);
    }
    std::vector<double> sorted = residual;
    std::nth_element(sorted.begin(), sorted.begin() + n / 2, sorted.end());
    // Robust scale (MAD of the residual norms), floored so a perfect fit does not reject everything.
    const double scale = std::max(1.4826 * sorted[static_cast<size_t>(n / 2)], 0.02);
    const double c = 4.685 * scale;
    cv::Mat w_a(n, terms, CV_64F);
    cv::Mat w_vx(n, 1, CV_64F), w_vy(n, 1, CV_64F);
    int used = 0;
    for (int i = 0; i < n; ++i) {
      const double u = residual[static_cast<size_t>(i)] / c;
      const double w = u < 1.0 ? (1.0 - u * u) * (1.0 - u * u) : 0.0;
      used += w > 0.0 ? 1 : 0;
      w_a.row(i) = a.row(i) * w;
      w_vx.at<double>(i) = velocities[static_cast<size_t>(i)][0] * w;
      w_vy.at<double>(i) = velocities[static_cast<size_t>(i)][1] * w;
    }
    if (used < 3 * terms) break;
    const cv::Mat normal = a.t() * w_a;
    cv::Mat next_x, next_y;
    if (!cv::solve(normal, a.t() * w_vx, next_x, cv::DECOMP_CHOLESKY) ||
        !cv::solve(normal, a.t() * w_vy, next_y, cv::DECOMP_CHOLESKY)) {
      break;
    }
    coef_x = next_x;
    coef_y = next_y;
  }
  if (!cv::checkRange(coef_x) || !cv::checkRange(coef_y)) return;
  cx_.assign(coef_x.begin<double>(), coef_x.end<double>());
  cy_.assign(coef_y.begin<double>(), coef_y.end<double>());
}

cv::Vec2d BackgroundFlow::field(const cv::Point2f& p) const {
  if (cx_.empty()) return {0.0, 0.0};
  const auto b = basis(p);
  double fx = 0, fy = 0;
  for (size_t i = 0; i < b.size(); ++i) {
    fx += cx_[i] * b[i];
    fy += cy_[i] * b[i];
  }
  return {fx, fy};
}

}  // namespace uavmot::motion
