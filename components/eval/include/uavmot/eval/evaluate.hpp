#pragma once
// Scores predictions against ground truth (docs/eval.md):
//   - paper Table I: completeness per moving object per frame (correct / under- / over-segmented / missed)
//   - paper Table II: mean absolute errors of cx, cy, width, length over correct instances (px and m)
//   - false alarms, and how many of them sit on parked vehicles or on static structures
//   - CLEAR MOT, IDF1 and HOTA as TrackEval computes them, at IoU 0.5 and 0.3
//   - homography transfer error and moving-feature precision/recall when those are given
//
//   auto result = uavmot::eval::evaluate(sequence, predictions, {});
//   EXPECT_GT(result.completeness.correct_rate(), 0.8);

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "uavmot/core/error.hpp"
#include "uavmot/eval/predictions.hpp"
#include "uavmot/eval/sequence.hpp"

namespace uavmot::eval {

struct EvalOptions {
  // Table I association: a predicted box belongs to a ground-truth object when it covers at
  // least `min_object_coverage` of the object's area, or when at least `min_box_on_object`
  // of the box's own area lies on the object.
  double min_object_coverage = 0.5;
  double min_box_on_object = 0.5;
  // Moving objects less visible than this (cut by the image border) are "don't care": not
  // counted when missed, and predictions on them are not false alarms.
  double min_visibility = 0.5;
  // IoU thresholds for CLEAR MOT / IDF1 / HOTA (TrackEval uses 0.5).
  std::vector<double> iou_thresholds{0.5, 0.3};
  // Use oriented-box IoU for the tracking metrics when both sides have oriented boxes
  // (TrackEval's MOT benchmark uses axis-aligned boxes: false).
  bool oriented_iou = false;
  // Features within this distance (px) of a moving object's pixels but not on them are ambiguous.
  double feature_tolerance_px = 1.5;
  // Frames to score: [first_frame, last_frame]; 0 = from the first / to the last frame.
  int64_t first_frame = 0;
  int64_t last_frame = 0;
};

// The instances of one band of apparent size: where a chain loses small or far-away vehicles.
struct SizeBand {
  double min_length_px = 0.0, max_length_px = 0.0;  // [min, max) of the object's length in the image; max 0: no limit
  int64_t instances = 0, correct = 0, missed = 0;
  double rate(int64_t n) const { return instances > 0 ? static_cast<double>(n) / static_cast<double>(instances) : 0.0; }
  double correct_rate() const { return rate(correct); }
};

// Bands by the length in px (the oriented box's longer side; of the MOTChallenge box without one):
// under 10 px (the `small` preset's 8 px cars, far field of an oblique view), 10-20 (`paper`'s 13-15),
// 20 and over.
std::vector<SizeBand> default_size_bands();

// Paper Table I. Instances are (moving object, frame) pairs.
struct Completeness {
  int64_t instances = 0;
  int64_t correct = 0;
  int64_t under_segmented = 0;  // merged with another moving object (each merged object counts)
  int64_t over_segmented = 0;   // split into two or more boxes (counts once)
  int64_t missed = 0;
  std::vector<SizeBand> by_length = default_size_bands();  // the same instances by apparent size
  double rate(int64_t n) const { return instances > 0 ? static_cast<double>(n) / static_cast<double>(instances) : 0.0; }
  double correct_rate() const { return rate(correct); }
};

// Paper Table II: mean absolute errors over correct instances.
struct Precision {
  int64_t samples = 0;
  bool oriented = false;  // errors from oriented boxes (true) or axis-aligned boxes (false)
  double error_x_px = 0.0, error_y_px = 0.0, error_width_px = 0.0, error_length_px = 0.0;
  double error_x_m = 0.0, error_y_m = 0.0, error_width_m = 0.0, error_length_m = 0.0;  // 0 when the GSD is unknown
};

struct FalseAlarms {
  int64_t boxes = 0;            // predicted boxes scored
  int64_t false_alarms = 0;     // boxes on no moving object
  int64_t on_parked = 0;        // of those, on a parked vehicle
  int64_t on_stopped = 0;       // of those, on a temporarily stopped (not parked) vehicle
  // Of the false alarms, those on a static 3-D structure (building, tree or wall; counted
  // only when the sequence has structures, by the kind it overlaps most).
  bool structures_known = false;
  int64_t on_structure = 0;
  int64_t on_building = 0, on_tree = 0, on_wall = 0;
  int64_t frames = 0;
  double per_frame() const { return frames > 0 ? static_cast<double>(false_alarms) / static_cast<double>(frames) : 0.0; }
  double on_structure_per_frame() const { return frames > 0 ? static_cast<double>(on_structure) / static_cast<double>(frames) : 0.0; }
};

struct ClearMot {
  double threshold = 0.5;
  int64_t gt_detections = 0, tracker_detections = 0;
  int64_t tp = 0, fp = 0, fn = 0, id_switches = 0, fragmentations = 0;
  int64_t gt_ids = 0, mostly_tracked = 0, partially_tracked = 0, mostly_lost = 0;
  double mota = 0.0, motp = 0.0;
  // Identity (Ristani et al.).
  int64_t idtp = 0, idfp = 0, idfn = 0;
  double idf1 = 0.0, idp = 0.0, idr = 0.0;
  // HOTA at this one threshold (alpha).
  double hota = 0.0, deta = 0.0, assa = 0.0, loca = 0.0;
};

// HOTA averaged over alpha = 0.05..0.95 as TrackEval reports it.
struct HotaSummary {
  double hota = 0.0, deta = 0.0, assa = 0.0, loca = 0.0;
};

struct HomographyErrors {
  int64_t frames = 0;        // frames with both an estimate and the truth (frame 1 excluded)
  int64_t missing = 0;       // frames with the truth but no estimate
  double mean_px = 0.0, p95_px = 0.0, max_px = 0.0;  // over a 16 x 16 grid of points per frame
  double worst_frame_mean_px = 0.0;
  int64_t worst_frame = 0;
};

struct FeatureClassification {
  int64_t features = 0;
  int64_t true_positive = 0, false_positive = 0, false_negative = 0, true_negative = 0;
  int64_t ambiguous = 0;          // near a moving object's edge: not scored
  int64_t frames_without_mask = 0;
  double precision() const {
    return true_positive + false_positive > 0 ? static_cast<double>(true_positive) / static_cast<double>(true_positive + false_positive) : 0.0;
  }
  double recall() const {
    return true_positive + false_negative > 0 ? static_cast<double>(true_positive) / static_cast<double>(true_positive + false_negative) : 0.0;
  }
};

struct EvaluationResult {
  SequenceInfo sequence;
  int64_t frames = 0;
  Completeness completeness;
  Precision precision;
  FalseAlarms false_alarms;
  bool has_identities = false;
  std::vector<ClearMot> tracking;  // one per IoU threshold (empty without identities)
  std::optional<HotaSummary> hota_averaged;
  std::optional<HomographyErrors> homography;
  std::optional<FeatureClassification> features;
};

// Throws InvalidArgument on bad options.
EvaluationResult evaluate(const Sequence& sequence, const Predictions& predictions, const EvalOptions& options = {});

// A readable multi-line table and the same numbers as JSON.
std::string format_table(const EvaluationResult& result);
nlohmann::ordered_json to_json(const EvaluationResult& result);

}  // namespace uavmot::eval
