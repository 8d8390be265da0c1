#pragma once
// Ceres refinement of a homography over its inliers: robust loss (Cauchy or Huber) on the
// symmetric transfer error, in normalised coordinates, single-threaded (deterministic).

#include <vector>

#include <opencv2/core/types.hpp>

#include "uavmot/core/homography.hpp"
#include "uavmot/motion/motion_options.hpp"

namespace uavmot::motion {

// Refines `initial` (src -> dst) over the correspondences flagged in `use`. Returns `initial`
// unchanged when fewer than 4 are flagged or the solution is not finite.
Homography refine_homography(const Homography& initial, const std::vector<cv::Point2f>& src,
                             const std::vector<cv::Point2f>& dst, const std::vector<unsigned char>& use,
                             const MotionOptions& options);

}  // namespace uavmot::motion
