#pragma once
// Where the image changed once the camera's motion is taken out: the previous frame warped by the
// frame's homography against this one. Moving vehicles (and, under parallax, structure) light up;
// the ground does not. The detector seeds features there, so a small vehicle crossing a grid cell
// that already holds a ground feature still gets one (docs/motion.md, "Features seeded on change").

#include <opencv2/core/mat.hpp>

#include "uavmot/core/homography.hpp"
#include "uavmot/motion/motion_options.hpp"

namespace uavmot::motion {

// CV_8UC1 mask of `current`'s size, 255 where |current - warped previous| exceeds
// max(change_min_grey, change_threshold_sigma x the difference's robust sigma), 0 elsewhere and
// where the warped previous frame does not reach. `previous_to_current` maps previous to current
// pixels. Empty when either image is empty or their sizes differ.
cv::Mat changed_pixels(const cv::Mat& previous, const cv::Mat& current, const Homography& previous_to_current,
                       const MotionOptions& options);

}  // namespace uavmot::motion
