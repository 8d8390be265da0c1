#include "feature_recentring.hpp"

#include <cmath>

namespace uavmot::segmentation {

std::vector<cv::Point2d> features_within(const OrientedBox& box, double margin_px, const std::vector<cv::Point2d>& points) {
  OrientedBox grown = box;
  grown.length += 2.0 * margin_px;
  grown.width += 2.0 * margin_px;
  const BoxFrame frame(grown);
  std::vector<cv::Point2d> inside;
  for (const auto& p : points) {
    if (frame.contains(p)) inside.push_back(p);
  }
  return inside;
}

double mean_offset_across(const OrientedBox& box, const std::vector<cv::Point2d>& points) {
  if (points.empty()) return 0.0;
  const BoxFrame frame(box);
  double sum = 0.0;  // across, in widths
  for (const auto& p : points) sum += frame.to_box_coordinates(p).y;
  return sum / static_cast<double>(points.size()) * box.width;
}

OrientedBox recentred_on_features(const OrientedBox& box, const std::vector<cv::Point2d>& features,
                                  double min_offset_fraction) {
  if (min_offset_fraction <= 0.0 || features.size() < 2) return box;
  const double across = mean_offset_across(box, features);
  if (!(std::abs(across) > min_offset_fraction * box.width)) return box;  // also NaN
  OrientedBox moved = box;
  const cv::Point2d centre = from_box_coordinates(box, {0.0, across / box.width});
  moved.cx = centre.x;
  moved.cy = centre.y;
  return moved;
}

}  // namespace uavmot::segmentation
