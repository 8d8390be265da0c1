#pragma once
// A corner right beside a vehicle is tracked by an LK window that is mostly vehicle, so it moves
// with the vehicle while its own centre is ground: a "dragged" feature, reported moving where
// nothing moves (most of the simulator's false moving features lie 1.5-6 px beside a vehicle).
// Its centre tells: a small patch around the feature matches the previous frame better where the
// ground there was (the homography) than where the feature came from (LK).

#include <opencv2/core/mat.hpp>
#include <opencv2/core/types.hpp>

#include "uavmot/core/homography.hpp"

namespace uavmot::motion {

struct CentreCheck {
  int radius_px = 2;            // the centre patch is (2 r + 1)^2 pixels
  double ratio = 0.8;           // dragged when the ground's mismatch is below this x the feature's own
  double min_difference = 2.0;  // ... and the feature's own mismatch is above this (RMS grey levels)
};

// True when the centre of a feature tracked from `from` (previous frame) to `to` (current frame)
// follows the background under `h` (previous -> current) clearly better than its own track.
bool centre_follows_background(const cv::Mat& previous, const cv::Mat& current, cv::Point2f from, cv::Point2f to,
                               const Homography& h, const CentreCheck& check);

}  // namespace uavmot::motion
