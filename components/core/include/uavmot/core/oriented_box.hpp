#pragma once
// Oriented boxes in the continuous OpenCV image frame (docs/conventions.md):
// centre (cx, cy), `width` across and `length` along the object's heading,
// `angle_deg` of the length axis from the image x-axis, in (-90, 90].

#include <array>

#include <opencv2/core/types.hpp>

namespace uavmot {

struct OrientedBox {
  double cx = 0.0;
  double cy = 0.0;
  double width = 0.0;   // across the heading
  double length = 0.0;  // along the heading
  double angle_deg = 0.0;

  bool operator==(const OrientedBox& other) const = default;
};

// Maps any angle to the equivalent length-axis angle in (-90, 90].
double normalize_axis_angle_deg(double angle_deg);

// Smallest signed difference a - b between two axis angles, in (-90, 90].
double axis_angle_difference_deg(double a_deg, double b_deg);

// From cv::minAreaRect output: picks the longer side as `length`.
OrientedBox oriented_box_from_rotated_rect(const cv::RotatedRect& rect);
cv::RotatedRect to_rotated_rect(const OrientedBox& box);

// Corners in order around the box (continuous coordinates).
std::array<cv::Point2d, 4> box_corners(const OrientedBox& box);

// Axis-aligned box around the oriented box: x = left, y = top (continuous).
cv::Rect2d axis_aligned_bounds(const OrientedBox& box);
// The whole pixels (centres at integer coordinates) that axis_aligned_bounds() reaches: from the
// floor of its left / top to the ceiling of its right / bottom, both included. `box` must be finite.
cv::Rect pixel_bounds(const OrientedBox& box);

double box_area(const OrientedBox& box);
// Area of the intersection of two oriented boxes (exact polygon clipping).
double intersection_area(const OrientedBox& a, const OrientedBox& b);
double intersection_over_union(const OrientedBox& a, const OrientedBox& b);
bool box_contains(const OrientedBox& box, const cv::Point2d& point);

// Position of `point` in the box's own frame, normalised so the box spans [-0.5, 0.5]^2
// (u along length, v across). Used to store where a feature sits on an object.
cv::Point2d to_box_coordinates(const OrientedBox& box, const cv::Point2d& point);
cv::Point2d from_box_coordinates(const OrientedBox& box, const cv::Point2d& uv);

// One box's axes, for testing many points against it: the sine and cosine once instead of per
// point (per pixel in the segmentation's shift check). The same arithmetic as the free functions
// above, which use it, so the answers are the same to the bit.
class BoxFrame {
 public:
  explicit BoxFrame(const OrientedBox& box);
  cv::Point2d to_box_coordinates(const cv::Point2d& point) const;
  bool contains(const cv::Point2d& point) const;

 private:
  OrientedBox box_;
  double cos_ = 1.0, sin_ = 0.0;
};

bool is_finite(const OrientedBox& box);

}  // namespace uavmot
