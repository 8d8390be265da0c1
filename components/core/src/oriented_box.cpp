#include "uavmot/core/oriented_box.hpp"

#include <cmath>
#include <vector>

#include <opencv2/imgproc.hpp>

namespace uavmot {
namespace {
constexpr double kPi = 3.14159265358979323846;
double deg_to_rad(double deg) { return deg * kPi / 180.0; }

// Sutherland-Hodgman clipping of a polygon by a convex polygon (both counter-clockwise or both clockwise).
double polygon_area(const std::vector<cv::Point2d>& poly) {
  double twice_area = 0.0;
  for (size_t i = 0; i < poly.size(); ++i) {
    const cv::Point2d& p = poly[i];
    const cv::Point2d& q = poly[(i + 1) % poly.size()];
    twice_area += p.x * q.y - q.x * p.y;
  }
  return 0.5 * std::abs(twice_area);
}

double cross(const cv::Point2d& o, const cv::Point2d& a, const cv::Point2d& b) {
  return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}

std::vector<cv::Point2d> clip_convex(std::vector<cv::Point2d> subject, const std::array<cv::Point2d, 4>& clip) {
  // Orientation of the clip polygon decides which side is "inside".
  const double orientation = cross(clip[0], clip[1], clip[2]) >= 0.0 ? 1.0 : -1.0;
  for (size_t e = 0; e < clip.size() && !subject.empty(); ++e) {
    const cv::Point2d& a = clip[e];
    const cv::Point2d& b = clip[(e + 1) % clip.size()];
    std::vector<cv::Point2d> output;
    output.reserve(subject.size() + 2);
    for (size_t i = 0; i < subject.size(); ++i) {
      const cv::Point2d& p = subject[i];
      const cv::Point2d& q = subject[(i + 1) % subject.size()];
      const double side_p = orientation * cross(a, b, p);
      const double side_q = orientation * cross(a, b, q);
      if (side_p >= 0.0) output.push_back(p);
      if ((side_p >= 0.0) != (side_q >= 0.0)) {
        const double t = side_p / (side_p - side_q);
        output.push_back(p + t * (q - p));
      }
    }
    subject = std::move(output);
  }
  return subject;
}
}  // namespace

double normalize_axis_angle_deg(double angle_deg) {
  double a = std::fmod(angle_deg, 180.0);
  if (a <= -90.0) a += 180.0;
  if (a > 90.0) a -= 180.0;
  return a;
}

double axis_angle_difference_deg(double a_deg, double b_deg) {
  return normalize_axis_angle_deg(a_deg - b_deg);
}

OrientedBox oriented_box_from_rotated_rect(const cv::RotatedRect& rect) {
  OrientedBox box;
  box.cx = rect.center.x;
  box.cy = rect.center.y;
  // cv::RotatedRect's angle is that of its `width` side.
  if (rect.size.width >= rect.size.height) {
    box.length = rect.size.width;
    box.width = rect.size.height;
    box.angle_deg = normalize_axis_angle_deg(rect.angle);
  } else {
    box.length = rect.size.height;
    box.width = rect.size.width;
    box.angle_deg = normalize_axis_angle_deg(rect.angle + 90.0);
  }
  return box;
}

cv::RotatedRect to_rotated_rect(const OrientedBox& box) {
  return cv::RotatedRect(cv::Point2f(static_cast<float>(box.cx), static_cast<float>(box.cy)),
                         cv::Size2f(static_cast<float>(box.length), static_cast<float>(box.width)),
                         static_cast<float>(box.angle_deg));
}

std::array<cv::Point2d, 4> box_corners(const OrientedBox& box) {
  const double a = deg_to_rad(box.angle_deg);
  const cv::Point2d along(std::cos(a) * box.length / 2.0, std::sin(a) * box.length / 2.0);
  const cv::Point2d across(-std::sin(a) * box.width / 2.0, std::cos(a) * box.width / 2.0);
  const cv::Point2d c(box.cx, box.cy);
  return {c - along - across, c + along - across, c + along + across, c - along + across};
}

cv::Rect2d axis_aligned_bounds(const OrientedBox& box) {
  const auto corners = box_corners(box);
  double min_x = corners[0].x, max_x = corners[0].x, min_y = corners[0].y, max_y = corners[0].y;
  for (const auto& p : corners) {
    min_x = std::min(min_x, p.x);
    max_x = std::max(max_x, p.x);
    min_y = std::min(min_y, p.y);
    max_y = std::max(max_y, p.y);
  }
  return {min_x, min_y, max_x - min_x, max_y - min_y};
}

cv::Rect pixel_bounds(const OrientedBox& box) {
  const cv::Rect2d r = axis_aligned_bounds(box);
  return cv::Rect(cv::Point(static_cast<int>(std::floor(r.x)), static_cast<int>(std::floor(r.y))),
                  cv::Point(static_cast<int>(std::ceil(r.br().x)) + 1, static_cast<int>(std::ceil(r.br().y)) + 1));
}

double box_area(const OrientedBox& box) { return std::max(0.0, box.width) * std::max(0.0, box.length); }

double intersection_area(const OrientedBox& a, const OrientedBox& b) {
  if (box_area(a) <= 0.0 || box_area(b) <= 0.0) return 0.0;
  // Cheap reject on circumscribed circles before clipping (squared: glibc's hypot is slow, and the
  // trackers and segmenter test thousands of pairs a frame).
  const double ra = 0.5 * std::sqrt(a.width * a.width + a.length * a.length);
  const double rb = 0.5 * std::sqrt(b.width * b.width + b.length * b.length);
  const double dx = a.cx - b.cx, dy = a.cy - b.cy;
  if (dx * dx + dy * dy > (ra + rb) * (ra + rb)) return 0.0;
  const auto ca = box_corners(a);
  const auto cb = box_corners(b);
  const auto clipped = clip_convex(std::vector<cv::Point2d>(ca.begin(), ca.end()), cb);
  return clipped.size() < 3 ? 0.0 : polygon_area(clipped);
}

double intersection_over_union(const OrientedBox& a, const OrientedBox& b) {
  const double inter = intersection_area(a, b);
  const double uni = box_area(a) + box_area(b) - inter;
  return uni > 0.0 ? inter / uni : 0.0;
}

BoxFrame::BoxFrame(const OrientedBox& box) : box_(box) {
  const double a = deg_to_rad(box.angle_deg);
  cos_ = std::cos(a);
  sin_ = std::sin(a);
}

cv::Point2d BoxFrame::to_box_coordinates(const cv::Point2d& point) const {
  const double dx = point.x - box_.cx;
  const double dy = point.y - box_.cy;
  const double along = dx * cos_ + dy * sin_;
  const double across = -dx * sin_ + dy * cos_;
  return {box_.length > 0.0 ? along / box_.length : 0.0, box_.width > 0.0 ? across / box_.width : 0.0};
}

bool BoxFrame::contains(const cv::Point2d& point) const {
  const cv::Point2d uv = to_box_coordinates(point);
  return std::abs(uv.x) <= 0.5 && std::abs(uv.y) <= 0.5;
}

cv::Point2d to_box_coordinates(const OrientedBox& box, const cv::Point2d& point) {
  return BoxFrame(box).to_box_coordinates(point);
}

cv::Point2d from_box_coordinates(const OrientedBox& box, const cv::Point2d& uv) {
  const double a = deg_to_rad(box.angle_deg);
  const double along = uv.x * box.length;
  const double across = uv.y * box.width;
  return {box.cx + along * std::cos(a) - across * std::sin(a), box.cy + along * std::sin(a) + across * std::cos(a)};
}

bool box_contains(const OrientedBox& box, const cv::Point2d& point) { return BoxFrame(box).contains(point); }

bool is_finite(const OrientedBox& box) {
  return std::isfinite(box.cx) && std::isfinite(box.cy) && std::isfinite(box.width) && std::isfinite(box.length) &&
         std::isfinite(box.angle_deg);
}

}  // namespace uavmot
