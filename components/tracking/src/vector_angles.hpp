#pragma once
// Directions of image-plane vectors (velocities, travel) in degrees, as the tracker compares them.

#include <algorithm>
#include <cmath>

#include <opencv2/core/matx.hpp>

namespace uavmot::tracking {

// The direction of `v` from +x towards +y, in (-180, 180].
inline double direction_deg(const cv::Vec2d& v) { return std::atan2(v[1], v[0]) * 180.0 / M_PI; }

// The angle between two non-zero vectors, in [0, 180].
inline double angle_between_deg(const cv::Vec2d& a, const cv::Vec2d& b) {
  return std::acos(std::clamp(a.dot(b) / (cv::norm(a) * cv::norm(b)), -1.0, 1.0)) * 180.0 / M_PI;
}

}  // namespace uavmot::tracking
