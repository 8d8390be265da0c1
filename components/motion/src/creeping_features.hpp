#pragma once
// Vehicles creeping in a queue move 0.05-0.15 px/frame, at or under the classifier's speed floor in
// frames without 3-D structure. A lower floor finds them but also takes ground corners beside a
// passing car whose LK window is partly car: they move with a fraction of its velocity. What tells
// the two apart is the neighbourhood: a creeping car's corners have neighbours about as slow, a
// dragged corner has one several times faster going its way (docs/motion.md, "creeping vehicles").

#include <vector>

#include <opencv2/core/matx.hpp>
#include <opencv2/core/types.hpp>

namespace uavmot::motion {

struct CreepRule {
  double creep_floor_px = 0.0;     // the lower floor (px/frame); at or above `floor_px` the rule is off
  double floor_px = 0.0;           // the normal floor: faster features need no rule
  double neighbour_radius_px = 0;  // how far a faster neighbour is looked for
  double neighbour_ratio = 2.0;    // a neighbour this many times as fast, going the same way, vetoes
  int min_support = 2;             // candidates within the radius going alike (itself included) needed
};

// For each feature (position, decided velocity; `decidable` false for features not classified this
// frame): whether it may be judged against the creep floor, i.e. its speed lies in
// [creep_floor_px, floor_px), no other decidable feature within neighbour_radius_px moves more
// than neighbour_ratio times as fast within 60 degrees of its direction, and at least min_support
// such candidates (itself included) within that radius go its way at a pace within neighbour_ratio
// of its own.
std::vector<unsigned char> creeping_features(const std::vector<cv::Point2f>& positions,
                                             const std::vector<cv::Vec2d>& velocities,
                                             const std::vector<unsigned char>& decidable, const CreepRule& rule);

}  // namespace uavmot::motion
