// Paper Table I (completeness), Table II (precision) and false alarms; rules in docs/eval.md.
#include <algorithm>
#include <cmath>
#include <set>

#include "metrics.hpp"
#include "polygon_overlap.hpp"

namespace uavmot::eval::detail {
namespace {

const std::vector<GroundTruthObject>& objects_in(const Sequence& sequence, int64_t frame) {
  static const std::vector<GroundTruthObject> none;
  auto it = sequence.objects.find(frame);
  return it == sequence.objects.end() ? none : it->second;
}

const std::vector<PredictedBox>& boxes_in(const Predictions& predictions, int64_t frame) {
  static const std::vector<PredictedBox> none;
  auto it = predictions.boxes.find(frame);
  return it == predictions.boxes.end() ? none : it->second;
}

// A box belongs to an object when it covers enough of the object, or lies mostly on it.
bool associated(const OrientedBox& object, const OrientedBox& box, const EvalOptions& options) {
  const double inter = intersection_area(object, box);
  if (inter <= 0.0) return false;
  return inter >= options.min_object_coverage * box_area(object) || inter >= options.min_box_on_object * box_area(box);
}

// The object's length in the image: its oriented box's longer side, else its MOTChallenge box's.
double apparent_length_px(const GroundTruthObject& o) {
  return o.oriented ? std::max(o.box.width, o.box.length) : std::max(o.bounds.width, o.bounds.height);
}

SizeBand& size_band(std::vector<SizeBand>& bands, double length_px) {
  for (SizeBand& b : bands) {
    if (length_px >= b.min_length_px && (b.max_length_px <= 0.0 || length_px < b.max_length_px)) return b;
  }
  return bands.back();  // bands cover [0, inf); only a NaN length gets here
}

const std::vector<StructureOutline>& structures_in(const Sequence& sequence, int64_t frame) {
  static const std::vector<StructureOutline> none;
  auto it = sequence.structures.find(frame);
  return it == sequence.structures.end() ? none : it->second;
}

// The structure a box belongs to by the vehicle rule (covers enough of it, or lies mostly on
// it), the one it overlaps most; nullptr when none.
const StructureOutline* structure_under(const std::vector<StructureOutline>& structures, const OrientedBox& box,
                                        const EvalOptions& options) {
  const StructureOutline* best = nullptr;
  double best_overlap = 0.0;
  for (const StructureOutline& s : structures) {
    const double inter = intersection_area(box, s.outline);
    if (inter <= best_overlap) continue;
    if (inter >= options.min_box_on_object * box_area(box) || inter >= options.min_object_coverage * polygon_area(s.outline)) {
      best = &s;
      best_overlap = inter;
    }
  }
  return best;
}

}  // namespace

std::vector<int64_t> frames_to_score(const Sequence& sequence, const EvalOptions& options) {
  const int64_t first = options.first_frame > 0 ? options.first_frame : 1;
  const int64_t last = options.last_frame > 0 ? std::min(options.last_frame, sequence.info.length) : sequence.info.length;
  std::vector<int64_t> frames;
  for (int64_t f = first; f <= last; ++f) frames.push_back(f);
  return frames;
}

bool is_scored(const GroundTruthObject& o, const EvalOptions& options) {
  return o.moving && o.visibility >= options.min_visibility;
}

bool is_ignored(const GroundTruthObject& o, const EvalOptions& options) {
  return !o.parked && !is_scored(o, options);
}

OrientedBox overlap_box(const PredictedBox& box) {
  if (box.oriented) return *box.oriented;
  return {box.bounds.x + box.bounds.width / 2.0, box.bounds.y + box.bounds.height / 2.0, box.bounds.height, box.bounds.width, 0.0};
}

void segmentation_metrics(const Sequence& sequence, const Predictions& predictions, const EvalOptions& options,
                          const std::vector<int64_t>& frames, Completeness& completeness, Precision& precision,
                          FalseAlarms& false_alarms) {
  double sum_x = 0, sum_y = 0, sum_w = 0, sum_l = 0;
  bool all_oriented = true;
  false_alarms.structures_known = sequence.has_structures;
  for (const int64_t frame : frames) {
    const auto& objects = objects_in(sequence, frame);
    const auto& boxes = boxes_in(predictions, frame);
    std::vector<OrientedBox> pred(boxes.size());
    for (size_t p = 0; p < boxes.size(); ++p) pred[p] = overlap_box(boxes[p]);
    // assoc[g][p]: box p belongs to object g.
    std::vector<std::vector<char>> assoc(objects.size(), std::vector<char>(boxes.size(), 0));
    for (size_t g = 0; g < objects.size(); ++g)
      for (size_t p = 0; p < boxes.size(); ++p) assoc[g][p] = associated(objects[g].box, pred[p], options);
    // How many moving objects each box covers (merges).
    std::vector<int> moving_per_box(boxes.size(), 0);
    for (size_t g = 0; g < objects.size(); ++g)
      if (objects[g].moving)
        for (size_t p = 0; p < boxes.size(); ++p) moving_per_box[p] += assoc[g][p];

    for (size_t g = 0; g < objects.size(); ++g) {
      const GroundTruthObject& o = objects[g];
      if (!is_scored(o, options)) continue;
      ++completeness.instances;
      int segments = 0;
      bool merged = false;
      size_t only = 0;
      for (size_t p = 0; p < boxes.size(); ++p) {
        if (!assoc[g][p]) continue;
        ++segments;
        only = p;
        if (moving_per_box[p] >= 2) merged = true;
      }
      SizeBand& band = size_band(completeness.by_length, apparent_length_px(o));
      ++band.instances;
      if (segments == 0) {
        ++completeness.missed;
        ++band.missed;
      } else if (merged) {
        ++completeness.under_segmented;
      } else if (segments >= 2) {
        ++completeness.over_segmented;
      } else {
        ++completeness.correct;
        ++band.correct;
        const PredictedBox& b = boxes[only];
        const bool oriented = o.oriented && b.oriented.has_value();
        all_oriented = all_oriented && oriented;
        sum_x += std::abs(pred[only].cx - o.box.cx);
        sum_y += std::abs(pred[only].cy - o.box.cy);
        if (oriented) {
          sum_w += std::abs(b.oriented->width - o.box.width);
          sum_l += std::abs(b.oriented->length - o.box.length);
        } else {
          // Without orientation: short side against short side, long against long.
          sum_w += std::abs(std::min(b.bounds.width, b.bounds.height) - std::min(o.bounds.width, o.bounds.height));
          sum_l += std::abs(std::max(b.bounds.width, b.bounds.height) - std::max(o.bounds.width, o.bounds.height));
        }
        ++precision.samples;
      }
    }

    ++false_alarms.frames;
    for (size_t p = 0; p < boxes.size(); ++p) {
      ++false_alarms.boxes;
      bool on_moving = false, on_parked = false, on_stopped = false;
      for (size_t g = 0; g < objects.size(); ++g) {
        if (!assoc[g][p]) continue;
        if (objects[g].moving) on_moving = true;
        else if (objects[g].parked) on_parked = true;
        else on_stopped = true;
      }
      if (on_moving) continue;
      if (on_stopped && !on_parked) {
        ++false_alarms.on_stopped;  // a vehicle waiting at the stop line: not scored either way
        continue;
      }
      ++false_alarms.false_alarms;
      if (on_parked) ++false_alarms.on_parked;
      if (const StructureOutline* s = structure_under(structures_in(sequence, frame), pred[p], options)) {
        ++false_alarms.on_structure;
        ++(s->kind == "building" ? false_alarms.on_building : s->kind == "tree" ? false_alarms.on_tree : false_alarms.on_wall);
      }
    }
  }
  precision.oriented = precision.samples > 0 && all_oriented;
  if (precision.samples > 0) {
    const double n = static_cast<double>(precision.samples);
    precision.error_x_px = sum_x / n;
    precision.error_y_px = sum_y / n;
    precision.error_width_px = sum_w / n;
    precision.error_length_px = sum_l / n;
    const double gsd = sequence.info.gsd_m;
    precision.error_x_m = precision.error_x_px * gsd;
    precision.error_y_m = precision.error_y_px * gsd;
    precision.error_width_m = precision.error_width_px * gsd;
    precision.error_length_m = precision.error_length_px * gsd;
  }
}

}  // namespace uavmot::eval::detail
