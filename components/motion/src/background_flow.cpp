#include "background_flow.hpp"

#include <algorithm>
#include <cmath>

#include <opencv2/core.hpp>

namespace uavmot::motion {

int BackgroundFlow::basis(const cv::Point2f& p, double* out) const {
  // Coordinates scaled to [-1, 1] keep the normal equations well conditioned.
  const double x = 2.0 * p.x / std::max(1, size_.width - 1) - 1.0;
  const double y = 2.0 * p.y / std::max(1, size_.height - 1) - 1.0;
  double x_pow[kMaxDegree + 1], y_pow[kMaxDegree + 1];
  x_pow[0] = y_pow[0] = 1.0;
  for (int k = 1; k <= degree_; ++k) {
    x_pow[k] = x_pow[k - 1] * x;
    y_pow[k] = y_pow[k - 1] * y;
  }
  int n = 0;
  for (int total = 0; total <= degree_; ++total) {
    for (int i = total; i >= 0; --i) out[n++] = x_pow[i] * y_pow[total - i];
  }
  return n;
}

void BackgroundFlow::fit(const std::vector<cv::Point2f>& positions, const std::vector<cv::Vec2d>& velocities) {
  cx_.clear();
  cy_.clear();
  if (degree_ <= 0) return;
  const int terms = (degree_ + 1) * (degree_ + 2) / 2;
  const int n = static_cast<int>(positions.size());
  if (n < 3 * terms) return;
  // Row-major design matrix: one row of `terms` basis values per point (thousands of points per
  // frame with dense features, so no per-row allocation).
  std::vector<double> a(static_cast<size_t>(n) * static_cast<size_t>(terms));
  for (int i = 0; i < n; ++i) basis(positions[static_cast<size_t>(i)], &a[static_cast<size_t>(i) * terms]);
  std::vector<double> coef_x(static_cast<size_t>(terms), 0.0), coef_y(static_cast<size_t>(terms), 0.0);
  std::vector<double> residual(static_cast<size_t>(n));
  for (int iteration = 0; iteration < 6; ++iteration) {
    for (int i = 0; i < n; ++i) {
      const double* row = &a[static_cast<size_t>(i) * terms];
      double fx = 0, fy = 0;
      for (int j = 0; j < terms; ++j) {
        fx += row[j] * coef_x[static_cast<size_t>(j)];
        fy += row[j] * coef_y[static_cast<size_t>(j)];
      }
      residual[static_cast<size_t>(i)] =
          std::hypot(velocities[static_cast<size_t>(i)][0] - fx, velocities[static_cast<size_t>(i)][1] - fy);
    }
    std::vector<double> sorted = residual;
    std::nth_element(sorted.begin(), sorted.begin() + n / 2, sorted.end());
    // Robust scale (MAD of the residual norms), floored so a perfect fit does not reject everything.
    const double scale = std::max(1.4826 * sorted[static_cast<size_t>(n / 2)], 0.02);
    const double c = 4.685 * scale;
    // Weighted normal equations A^T W A c = A^T W v, accumulated row by row.
    cv::Mat normal = cv::Mat::zeros(terms, terms, CV_64F);
    cv::Mat rhs_x = cv::Mat::zeros(terms, 1, CV_64F), rhs_y = cv::Mat::zeros(terms, 1, CV_64F);
    int used = 0;
    for (int i = 0; i < n; ++i) {
      const double u = residual[static_cast<size_t>(i)] / c;
      if (u >= 1.0) continue;
      const double w = (1.0 - u * u) * (1.0 - u * u);
      ++used;
      const double* row = &a[static_cast<size_t>(i) * terms];
      const double wvx = w * velocities[static_cast<size_t>(i)][0], wvy = w * velocities[static_cast<size_t>(i)][1];
      for (int j = 0; j < terms; ++j) {
        const double wa = w * row[j];
        double* normal_row = normal.ptr<double>(j);
        for (int k = 0; k <= j; ++k) normal_row[k] += wa * row[k];
        rhs_x.at<double>(j) += row[j] * wvx;
        rhs_y.at<double>(j) += row[j] * wvy;
      }
    }
    if (used < 3 * terms) break;
    cv::completeSymm(normal);  // only the lower triangle was accumulated
    cv::Mat next_x, next_y;
    if (!cv::solve(normal, rhs_x, next_x, cv::DECOMP_CHOLESKY) || !cv::solve(normal, rhs_y, next_y, cv::DECOMP_CHOLESKY)) {
      break;
    }
    coef_x.assign(next_x.begin<double>(), next_x.end<double>());
    coef_y.assign(next_y.begin<double>(), next_y.end<double>());
  }
  for (int j = 0; j < terms; ++j) {
    if (!std::isfinite(coef_x[static_cast<size_t>(j)]) || !std::isfinite(coef_y[static_cast<size_t>(j)])) return;
  }
  cx_ = std::move(coef_x);
  cy_ = std::move(coef_y);
}

cv::Vec2d BackgroundFlow::field(const cv::Point2f& p) const {
  if (cx_.empty()) return {0.0, 0.0};
  double b[kMaxTerms];
  const int terms = basis(p, b);
  double fx = 0, fy = 0;
  for (int i = 0; i < terms; ++i) {
    fx += cx_[static_cast<size_t>(i)] * b[i];
    fy += cy_[static_cast<size_t>(i)] * b[i];
  }
  return {fx, fy};
}

}  // namespace uavmot::motion
