#pragma once
// A cheap, exact test of whether a grid cell can hold a corner at all. Most cells the corner
// search visits are flat ground or plain edges (the empty cells' staggered retries: 94 % of the
// searches on `hd` gave no candidate), and cv::cornerMinEigenVal costs about 15 us per cell; this
// test costs a fraction of that and never passes over a cell that cornerMinEigenVal would give a
// corner in (tests/corner_bound_test.cpp).

#include <opencv2/core/mat.hpp>

#include "uavmot/motion/motion_options.hpp"

namespace uavmot::motion {

// Whether any pixel of `cell` (of the 8-bit grey image) may reach options.min_corner_response in
// cv::cornerMinEigenVal(gray, eig, options.corner_block_size, 3). True near the image border,
// where the filters would read past it.
bool may_hold_corner(const cv::Mat& gray, const cv::Rect& cell, const MotionOptions& options);

}  // namespace uavmot::motion
