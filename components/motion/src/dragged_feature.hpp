#pragma once
// A corner right beside a vehicle is tracked by an LK window that is mostly vehicle, so it moves
// with the vehicle while its own centre is ground: a "dragged" feature, reported moving where
// nothing moves (most of the simulator's false moving features lie 1.5-6 px beside a vehicle).
// Its centre tells: a small patch around the feature matches the previous frame better where the
// ground there was (the homography) than where the feature came from (LK).

#include <opencv2/core/mat.hpp>
#include <opencv2/core/types.hpp>

#include "uavmot/core/homography.hpp"
#include "uavmot/motion/motion_options.hpp"

namespace uavmot::motion {

// True when the centre of a feature tracked from `from` (previous frame) to `to` (current frame)
// follows the background clearly better than its own track. `current_to_previous` is the inverse
// of the frame's homography (computed once per frame by the caller); the thresholds are the
// options' dragged_ratio, dragged_patch_radius_px and dragged_min_difference.
bool centre_follows_background(const cv::Mat& previous, const cv::Mat& current, cv::Point2f from, cv::Point2f to,
                               const Homography& current_to_previous, const MotionOptions& options);

}  // namespace uavmot::motion
