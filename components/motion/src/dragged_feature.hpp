#pragma once
// A corner right beside a vehicle is tracked by an LK window that is mostly vehicle, so it moves
// with the vehicle while its own centre is ground: a "dragged" feature, reported moving where
// nothing moves (most of the simulator's false moving features lie 1.5-6 px beside a vehicle).
// Its centre tells: a small patch around the feature matches the previous frame better where the
// ground there was (the homography) than where the feature came from (LK). Unless the centre is a
// line along the motion (a lane marking beside a car): it matches along the line either way, so the
// motion it reports is its window's, not its own (centre_gradient_along).

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

// The share of the grey-level gradient energy of the centre patch at `at` (`image`: CV_8UC1; the
// patch of dragged_patch_radius_px, central differences) that lies along `motion`: near 0 when the
// centre is a line or an edge parallel to its motion (a lane marking beside a car, whose window the
// car drags along it: the centre cannot show that motion, the aperture problem), about 0.5 for a
// corner. 1 for a patch without gradient, a zero motion or a patch outside the image (nothing to say).
double centre_gradient_along(const cv::Mat& image, cv::Point2f at, cv::Vec2d motion, const MotionOptions& options);

}  // namespace uavmot::motion
