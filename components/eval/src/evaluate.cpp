#include "uavmot/eval/evaluate.hpp"

#include <cmath>

#include "metrics.hpp"
#include "uavmot/core/error.hpp"

namespace uavmot::eval {

std::vector<SizeBand> default_size_bands() {
  std::vector<SizeBand> bands(3);
  bands[0].max_length_px = 10.0;
  bands[1].min_length_px = 10.0;
  bands[1].max_length_px = 20.0;
  bands[2].min_length_px = 20.0;
  return bands;
}

EvaluationResult evaluate(const Sequence& sequence, const Predictions& predictions, const EvalOptions& options) {
  const auto in_unit = [](double v) { return std::isfinite(v) && v >= 0.0 && v <= 1.0; };
  if (!in_unit(options.min_object_coverage) || !in_unit(options.min_box_on_object) || !in_unit(options.min_visibility))
    throw InvalidArgument("EvalOptions: coverage, box-on-object and visibility thresholds must lie in [0, 1]");
  if (options.min_object_coverage <= 0.0 || options.min_box_on_object <= 0.0)
    throw InvalidArgument("EvalOptions: association thresholds must be positive");
  for (double t : options.iou_thresholds)
    if (!(t > 0.0 && t <= 1.0)) throw InvalidArgument("EvalOptions: IoU thresholds must lie in (0, 1]");
  if (!(options.feature_tolerance_px >= 0.0)) throw InvalidArgument("EvalOptions: feature_tolerance_px must not be negative");
  if (options.first_frame > 0 && options.last_frame > 0 && options.first_frame > options.last_frame)
    throw InvalidArgument("EvalOptions: first_frame is after last_frame");

  EvaluationResult result;
  result.sequence = sequence.info;
  const std::vector<int64_t> frames = detail::frames_to_score(sequence, options);
  result.frames = static_cast<int64_t>(frames.size());
  detail::segmentation_metrics(sequence, predictions, options, frames, result.completeness, result.precision, result.false_alarms);

  result.has_identities = predictions.has_identities();
  if (result.has_identities) {
    for (double threshold : options.iou_thresholds) {
      const detail::TrackingData data = detail::prepare_tracking(sequence, predictions, options, frames, threshold);
      ClearMot m;
      detail::clear_mot(data, threshold, m);
      detail::identity(data, threshold, m);
      const HotaSummary h = detail::hota(data, threshold);
      m.hota = h.hota;
      m.deta = h.deta;
      m.assa = h.assa;
      m.loca = h.loca;
      result.tracking.push_back(m);
    }
    // TrackEval's headline HOTA: the mean over alpha = 0.05, 0.10, ..., 0.95 (distractors removed at 0.5).
    const detail::TrackingData data = detail::prepare_tracking(sequence, predictions, options, frames, 0.5);
    HotaSummary mean;
    for (int a = 1; a <= 19; ++a) {
      const HotaSummary h = detail::hota(data, 0.05 * a);
      mean.hota += h.hota / 19.0;
      mean.deta += h.deta / 19.0;
      mean.assa += h.assa / 19.0;
      mean.loca += h.loca / 19.0;
    }
    result.hota_averaged = mean;
  }
  if (!predictions.homographies.empty()) result.homography = detail::homography_errors(sequence, predictions, frames);
  if (!predictions.features.empty()) result.features = detail::feature_classification(sequence, predictions, options, frames);
  return result;
}

}  // namespace uavmot::eval
