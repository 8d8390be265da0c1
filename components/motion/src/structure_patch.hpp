#pragma once
// Whether a feature's pixels moved as static 3-D structure could have moved them.
//
// The plane + parallax step reads a feature's velocity only, and two kinds of static points pass
// it as movers: corners where a roof edge or a tree crown crosses ground texture (two layers in one
// LK window: the corner slides along the ground's edge, off its epipolar line) and points above the
// tallest structure the cap allows for (a unit on a 30 m roof). Their pixels still tell: each pixel
// of the patch is where the previous frame had it under some shift along the epipolar line, from 0
// (ground) to the cap (the tallest structure), one shift for the ground's pixels and another for
// the roof's. A vehicle's pixels are where its own track put them, and under no such shift.
//
// Both sides are scored alike, by the mean over the patch of each pixel's smallest difference over
// the same number of shifts: the structure's along the epipolar line from 0 to the cap (from -cap
// to the cap when structure lies on both sides of the plane), the track's along the same line
// around its own start, up to half the cap either way. A minimum over many shifts is smaller than one over few, even on
// noise; the same count keeps the comparison fair.

#include <opencv2/core/mat.hpp>
#include <opencv2/core/types.hpp>

#include "parallax_filter.hpp"
#include "uavmot/core/homography.hpp"
#include "uavmot/motion/motion_options.hpp"

namespace uavmot::motion {

struct PatchErrors {
  double structure = 0.0;  // mean grey-level difference, each pixel under its best structure shift
  double own = 0.0;        // ... under its best shift around the feature's own track
};

// The two errors of the patch around `to` (current frame), tracked from `from` (previous frame).
// `current_to_previous` is the inverse of the frame's homography (computed once per frame).
PatchErrors structure_patch_errors(const cv::Mat& previous, const cv::Mat& current, cv::Point2f from, cv::Point2f to,
                                   const Homography& current_to_previous, const ParallaxFilter::StructureMotion& structure,
                                   int radius_px);

// True when static structure explains the patch about as well as the track does: its error below
// options.structure_patch_ratio x the track's (never with the ratio at 0).
bool structure_explains_patch(const PatchErrors& errors, const MotionOptions& options);

}  // namespace uavmot::motion
