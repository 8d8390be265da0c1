#include "uavmot/core/homography.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include <opencv2/core.hpp>  // Matx::inv

#include "uavmot/core/image_bounds.hpp"

namespace uavmot {

Homography identity_homography() { return Homography::eye(); }

bool is_finite(const Homography& h) {
  for (int i = 0; i < 9; ++i) {
    if (!std::isfinite(h.val[i])) return false;
  }
  return true;
}

bool normalize_homography(Homography& h) {
  if (!is_finite(h) || std::abs(h(2, 2)) < 1e-12) return false;
  h = h * (1.0 / h(2, 2));
  return true;
}

cv::Point2d apply_homography(const Homography& h, const cv::Point2d& p) {
  const double x = h(0, 0) * p.x + h(0, 1) * p.y + h(0, 2);
  const double y = h(1, 0) * p.x + h(1, 1) * p.y + h(1, 2);
  const double w = h(2, 0) * p.x + h(2, 1) * p.y + h(2, 2);
  return {x / w, y / w};
}

double image_step_px(const Homography& h, const cv::Point2d& p) {
  const cv::Point2d moved = apply_homography(h, p);
  return std::hypot(moved.x - p.x, moved.y - p.y);
}

double frames_to_cross_view(const Homography& h, cv::Size image) {
  const double step_px = image_step_px(h, {0.5 * image.width, 0.5 * image.height});
  const int side = std::min(image.width, image.height);
  if (side <= 0 || !(step_px > 0.0)) return std::numeric_limits<double>::infinity();
  return side / step_px;
}

int frames_ground_in_view(const Homography& h, const cv::Point2d& p, cv::Size image, int max_frames) {
  const Homography back = h.inv();
  cv::Point2d q = p;
  for (int frames = 0; frames <= max_frames; ++frames) {
    q = apply_homography(back, q);
    if (!inside_image(q, image)) return frames;
  }
  return max_frames + 1;
}

cv::Matx22d homography_jacobian(const Homography& h, const cv::Point2d& p) {
  const double x = h(0, 0) * p.x + h(0, 1) * p.y + h(0, 2);
  const double y = h(1, 0) * p.x + h(1, 1) * p.y + h(1, 2);
  const double w = h(2, 0) * p.x + h(2, 1) * p.y + h(2, 2);
  const double w2 = w * w;
  return {(h(0, 0) * w - x * h(2, 0)) / w2, (h(0, 1) * w - x * h(2, 1)) / w2,
          (h(1, 0) * w - y * h(2, 0)) / w2, (h(1, 1) * w - y * h(2, 1)) / w2};
}

OrientedBox transform_box(const Homography& h, const OrientedBox& box) {
  const cv::Point2d centre = apply_homography(h, {box.cx, box.cy});
  const cv::Matx22d jac = homography_jacobian(h, {box.cx, box.cy});
  const double a = box.angle_deg * M_PI / 180.0;
  const cv::Vec2d along = jac * cv::Vec2d(std::cos(a), std::sin(a));
  const cv::Vec2d across = jac * cv::Vec2d(-std::sin(a), std::cos(a));
  OrientedBox out;
  out.cx = centre.x;
  out.cy = centre.y;
  out.length = box.length * cv::norm(along);
  out.width = box.width * cv::norm(across);
  out.angle_deg = normalize_axis_angle_deg(std::atan2(along[1], along[0]) * 180.0 / M_PI);
  return out;
}

std::vector<double> transfer_errors(const Homography& a, const Homography& b, int width, int height, int grid) {
  std::vector<double> errors;
  errors.reserve(static_cast<size_t>(grid * grid));
  for (int j = 0; j < grid; ++j) {
    for (int i = 0; i < grid; ++i) {
      const cv::Point2d p((i + 0.5) * width / grid - 0.5, (j + 0.5) * height / grid - 0.5);
      errors.push_back(cv::norm(apply_homography(a, p) - apply_homography(b, p)));
    }
  }
  return errors;
}

double mean_transfer_error(const Homography& a, const Homography& b, int width, int height, int grid) {
  const auto errors = transfer_errors(a, b, width, height, grid);
  return std::accumulate(errors.begin(), errors.end(), 0.0) / static_cast<double>(errors.size());
}

std::array<double, 9> to_row_major(const Homography& h) {
  std::array<double, 9> values{};
  for (int i = 0; i < 9; ++i) values[static_cast<size_t>(i)] = h.val[i];
  return values;
}

Homography from_row_major(const std::array<double, 9>& values) {
  Homography h;
  for (int i = 0; i < 9; ++i) h.val[i] = values[static_cast<size_t>(i)];
  return h;
}

}  // namespace uavmot
