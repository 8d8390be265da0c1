#pragma once
// The metric computations behind evaluate(); each works on the frames selected by the options.

#include <vector>

#include "uavmot/eval/evaluate.hpp"

namespace uavmot::eval::detail {

// Frames to score, in order.
std::vector<int64_t> frames_to_score(const Sequence& sequence, const EvalOptions& options);

// Is this ground-truth object scored (a moving object visible enough)?
bool is_scored(const GroundTruthObject& object, const EvalOptions& options);
// Is it "don't care" (stopped but not parked, or moving but mostly outside the image)?
bool is_ignored(const GroundTruthObject& object, const EvalOptions& options);

// The box used for area overlaps: oriented when known, else the axis-aligned box.
OrientedBox overlap_box(const PredictedBox& box);

// Paper Tables I and II and the false alarms.
void segmentation_metrics(const Sequence& sequence, const Predictions& predictions, const EvalOptions& options,
                          const std::vector<int64_t>& frames, Completeness& completeness, Precision& precision,
                          FalseAlarms& false_alarms);

// Per-frame data for the tracking metrics, with ids mapped to 0..n-1 (as TrackEval prepares it).
struct TrackingFrame {
  std::vector<int> gt_ids;
  std::vector<int> tracker_ids;
  std::vector<std::vector<double>> similarity;  // [gt][tracker] IoU
};
struct TrackingData {
  int gt_id_count = 0;
  int tracker_id_count = 0;
  int64_t gt_detections = 0;
  int64_t tracker_detections = 0;
  std::vector<TrackingFrame> frames;
};
// Predictions matched (IoU >= distractor_threshold) to "don't care" objects are removed first.
TrackingData prepare_tracking(const Sequence& sequence, const Predictions& predictions, const EvalOptions& options,
                              const std::vector<int64_t>& frames, double distractor_threshold);

void clear_mot(const TrackingData& data, double threshold, ClearMot& out);
void identity(const TrackingData& data, double threshold, ClearMot& out);
HotaSummary hota(const TrackingData& data, double alpha);

HomographyErrors homography_errors(const Sequence& sequence, const Predictions& predictions, const std::vector<int64_t>& frames);
FeatureClassification feature_classification(const Sequence& sequence, const Predictions& predictions,
                                             const EvalOptions& options, const std::vector<int64_t>& frames);

}  // namespace uavmot::eval::detail
