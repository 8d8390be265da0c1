#pragma once
// A gradient blob can take in static texture beside a vehicle (a lane marking or kerb along a
// road-grey car): its box then lies off to one side of the vehicle's own moving features. Moving
// such a box across onto the features puts it back on the vehicle.

#include <vector>

#include <opencv2/core/types.hpp>

#include "uavmot/core/oriented_box.hpp"

namespace uavmot::segmentation {

// The points inside `box` grown by `margin_px` on every side.
std::vector<cv::Point2d> features_within(const OrientedBox& box, double margin_px, const std::vector<cv::Point2d>& points);

// Mean signed distance (px) of `points` from `box`'s centre line, across its heading (positive
// toward +90 deg from the heading); 0 for no points.
double mean_offset_across(const OrientedBox& box, const std::vector<cv::Point2d>& points);

// `box` moved across its heading onto the mean of `features` (the features it holds) when that
// mean lies more than `min_offset_fraction` x its width from its centre line and there are at
// least two features; otherwise `box` unchanged. Size and angle are kept. 0 disables.
OrientedBox recentred_on_features(const OrientedBox& box, const std::vector<cv::Point2d>& features,
                                  double min_offset_fraction);

}  // namespace uavmot::segmentation
