#pragma once
// Hand-made ground truth and predictions for the metric tests.

#include "uavmot/eval/evaluate.hpp"

namespace uavmot::eval::testing {

inline GroundTruthObject object(int64_t id, double cx, double cy, double width, double length, double angle = 0.0,
                                bool moving = true, bool parked = false, double visibility = 1.0) {
  GroundTruthObject o;
  o.id = id;
  o.box = {cx, cy, width, length, angle};
  o.oriented = true;
  o.bounds = axis_aligned_bounds(o.box);
  o.moving = moving;
  o.parked = parked;
  o.visibility = visibility;
  return o;
}

inline PredictedBox oriented(int64_t id, double cx, double cy, double width, double length, double angle = 0.0) {
  PredictedBox p;
  p.id = id;
  p.oriented = OrientedBox{cx, cy, width, length, angle};
  p.bounds = axis_aligned_bounds(*p.oriented);
  return p;
}

inline Sequence empty_sequence(int64_t frames, double gsd = 0.5) {
  Sequence s;
  s.info.name = "hand";
  s.info.length = frames;
  s.info.width = 320;
  s.info.height = 240;
  s.info.gsd_m = gsd;
  for (int64_t f = 1; f <= frames; ++f) s.objects[f];
  return s;
}

}  // namespace uavmot::eval::testing
