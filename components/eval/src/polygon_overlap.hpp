#pragma once
// Overlap of a box with a convex polygon (a structure's silhouette), by exact clipping.

#include <vector>

#include <opencv2/core/types.hpp>

#include "uavmot/core/oriented_box.hpp"

namespace uavmot::eval::detail {

double polygon_area(const std::vector<cv::Point2d>& polygon);  // absolute, either orientation
// Area of box ∩ convex polygon; 0 when the polygon has fewer than three points.
double intersection_area(const OrientedBox& box, const std::vector<cv::Point2d>& convex);

}  // namespace uavmot::eval::detail
