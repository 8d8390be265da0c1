#pragma once
// Where in and around a region the pixels move with its cluster. A road-grey car's blob is mostly
// what lies beside it (its shadow, the lane marking or kerb it passes), so its box sits off the
// car; the car itself shows where the previous frame, shifted by the cluster's velocity, explains
// the pixels better than the previous frame at rest. Static texture is explained at rest, and an
// edge along the direction of travel is explained equally either way: neither pulls the centroid.

#include <optional>
#include <vector>

#include <opencv2/core/types.hpp>

#include "shift_check.hpp"

namespace uavmot::segmentation {

struct MotionEvidence {
  // Where the evidence's centroid lies across the box, px from its centre line (+ toward the box's
  // +y side, i.e. 90 degrees counter-clockwise in image terms from its length axis). Only across:
  // along the travel the evidence is lopsided, as the strip the vehicle has just left lies behind
  // a box drawn round it and the strip it has just entered inside it.
  double across_px = 0.0;
  double inside_fraction = 0.0;  // share of the evidence inside the box itself
  // Where it lies along the box, px from its centre (+ along the length axis): only meaningful over
  // a box lengthened past both ends of the vehicle (lengthen_px), where the strips it left and
  // entered both count.
  double along_px = 0.0;
};

// The motion evidence over `box` widened by `margin_px` on each long side: per pixel, the grey
// error of the previous frame at rest less that of the best shift of `search` (the one best over
// the widened box), averaged over 3 x 3 pixels and counted where positive. Not lengthened: a
// blob's ends are the vehicle's, and on a long vehicle seen in pieces the evidence at its nearer
// end pulled a piece off it (a truck on `paper` seed 3); `lengthen_px` lengthens it at each end where
// the box is only a guess (a cluster's box around one feature). Nothing when no shift is fast enough, the
// previous windows hold less than half of the widened box under every hypothesis, or no pixel
// shows evidence.
std::optional<MotionEvidence> motion_evidence(const ImageCrop& current, const OrientedBox& box, double margin_px,
                                              const ShiftSearch& search, const Homography& previous_from_current,
                                              const std::vector<ImageCrop>& previous, double lengthen_px = 0.0);

}  // namespace uavmot::segmentation
