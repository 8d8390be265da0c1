#pragma once
// Shi-Tomasi corners, detected only in grid cells that hold too few live features, so a frame
// with good coverage costs almost nothing and new texture entering the view is picked up.

#include <vector>

#include <opencv2/core/mat.hpp>
#include <opencv2/core/types.hpp>

#include "uavmot/motion/motion_options.hpp"

namespace uavmot::motion {

// New corners in `gray` (CV_8UC1): at least min_distance_px from every point of `existing` and
// from each other, at most features_per_cell per cell counting `existing`, no more than
// max_features in total, above min_corner_response. Deterministic order: cells row-major,
// strongest corner first within a cell.
std::vector<cv::Point2f> detect_missing_corners(const cv::Mat& gray, const std::vector<cv::Point2f>& existing,
                                                const MotionOptions& options);

}  // namespace uavmot::motion
