#include "feature_recentring.hpp"

#include <cmath>

namespace uavmot::segmentation {
namespace {
constexpr double kPi = 3.14159265358979323846;
}

std::vector<cv::Point2d> features_within(const OrientedBox& box, double margin_px, const std::vector<cv::Point2d>& points) {
  OrientedBox grown = box;
  grown.length += 2.0 * margin_px;
  grown.width += 2.0 * margin_px;
  std::vector<cv::Point2d> inside;
  for (const auto& p : points) {
    if (box_contains(grown, p)) inside.push_back(p);
  }
  return inside;
}

double mean_offset_across(const OrientedBox& box, const std::vector<cv::Point2d>& points) {
  if (points.empty()) return 0.0;
  const double theta = box.angle_deg * kPi / 180.0;
  const double ux = std::cos(theta), uy = std::sin(theta);
  double sum = 0.0;
  for (const auto& p : points) sum += -(p.x - box.cx) * uy + (p.y - box.cy) * ux;
  return sum / static_cast<double>(points.size());
}

OrientedBox recentred_on_features(const OrientedBox& box, const std::vector<cv::Point2d>& features,
                                  double min_offset_fraction) {
  if (min_offset_fraction <= 0.0 || features.size() < 2) return box;
  const double across = mean_offset_across(box, features);
  if (!(std::abs(across) > min_offset_fraction * box.width)) return box;  // also NaN
  const double theta = box.angle_deg * kPi / 180.0;
  OrientedBox moved = box;
  moved.cx -= across * std::sin(theta);
  moved.cy += across * std::cos(theta);
  return moved;
}

}  // namespace uavmot::segmentation
