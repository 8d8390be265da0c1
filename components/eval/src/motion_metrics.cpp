// Homography transfer errors and moving-feature classification against the simulator's truth.
#include <algorithm>
#include <cmath>
#include <map>

#include "metrics.hpp"

namespace uavmot::eval::detail {

HomographyErrors homography_errors(const Sequence& sequence, const Predictions& predictions, const std::vector<int64_t>& frames) {
  HomographyErrors out;
  std::vector<double> all;
  double sum = 0.0;
  for (const int64_t frame : frames) {
    if (frame < 2) continue;  // frame 1 has no previous frame
    auto truth = sequence.homographies.find(frame);
    if (truth == sequence.homographies.end()) continue;
    auto estimate = predictions.homographies.find(frame);
    if (estimate == predictions.homographies.end()) {
      ++out.missing;
      continue;
    }
    const std::vector<double> errors = transfer_errors(estimate->second, truth->second, sequence.info.width, sequence.info.height, 16);
    double frame_sum = 0.0;
    for (double e : errors) frame_sum += e;
    const double frame_mean = errors.empty() ? 0.0 : frame_sum / static_cast<double>(errors.size());
    if (frame_mean > out.worst_frame_mean_px || out.frames == 0) {
      out.worst_frame_mean_px = frame_mean;
      out.worst_frame = frame;
    }
    sum += frame_sum;
    all.insert(all.end(), errors.begin(), errors.end());
    ++out.frames;
  }
  if (!all.empty()) {
    out.mean_px = sum / static_cast<double>(all.size());
    std::sort(all.begin(), all.end());
    out.max_px = all.back();
    // Nearest-rank 95th percentile.
    const size_t rank = static_cast<size_t>(std::ceil(0.95 * static_cast<double>(all.size())));
    out.p95_px = all[std::max<size_t>(1, rank) - 1];
  }
  return out;
}

namespace {
enum class Truth { Moving, Stationary, Ambiguous };

Truth truth_from_mask(const cv::Mat& mask, const std::map<int64_t, bool>& moving_by_id, cv::Point2d p, double tolerance) {
  const auto id_at = [&](int x, int y) -> int64_t {
    if (x < 0 || y < 0 || x >= mask.cols || y >= mask.rows) return 0;
    return mask.type() == CV_16U ? mask.at<uint16_t>(y, x) : mask.at<int32_t>(y, x);
  };
  const auto is_moving = [&](int64_t id) {
    auto it = moving_by_id.find(id);
    return it != moving_by_id.end() && it->second;
  };
  const int x = static_cast<int>(std::lround(p.x)), y = static_cast<int>(std::lround(p.y));
  if (is_moving(id_at(x, y))) return Truth::Moving;
  const int r = static_cast<int>(std::ceil(tolerance));
  for (int yy = y - r; yy <= y + r; ++yy)
    for (int xx = x - r; xx <= x + r; ++xx)
      if ((xx - p.x) * (xx - p.x) + (yy - p.y) * (yy - p.y) <= tolerance * tolerance && is_moving(id_at(xx, yy)))
        return Truth::Ambiguous;
  return Truth::Stationary;
}

Truth truth_from_boxes(const std::vector<GroundTruthObject>& objects, cv::Point2d p, double tolerance) {
  Truth truth = Truth::Stationary;
  for (const auto& o : objects) {
    if (!o.moving) continue;
    if (box_contains(o.box, p)) return Truth::Moving;
    OrientedBox grown = o.box;
    grown.width += 2.0 * tolerance;
    grown.length += 2.0 * tolerance;
    if (box_contains(grown, p)) truth = Truth::Ambiguous;
  }
  return truth;
}
}  // namespace

FeatureClassification feature_classification(const Sequence& sequence, const Predictions& predictions,
                                             const EvalOptions& options, const std::vector<int64_t>& frames) {
  FeatureClassification out;
  static const std::vector<GroundTruthObject> none;
  for (const int64_t frame : frames) {
    auto fit = predictions.features.find(frame);
    if (fit == predictions.features.end() || fit->second.empty()) continue;
    auto oit = sequence.objects.find(frame);
    const auto& objects = oit == sequence.objects.end() ? none : oit->second;
    std::map<int64_t, bool> moving_by_id;
    for (const auto& o : objects) moving_by_id[o.id] = o.moving;
    const cv::Mat mask = sequence.id_mask ? sequence.id_mask(frame) : cv::Mat();
    if (mask.empty()) ++out.frames_without_mask;
    for (const PredictedFeature& f : fit->second) {
      ++out.features;
      const Truth truth = mask.empty() ? truth_from_boxes(objects, f.position, options.feature_tolerance_px)
                                       : truth_from_mask(mask, moving_by_id, f.position, options.feature_tolerance_px);
      if (truth == Truth::Ambiguous) {
        ++out.ambiguous;
      } else if (truth == Truth::Moving) {
        (f.moving ? out.true_positive : out.false_negative) += 1;
      } else {
        (f.moving ? out.false_positive : out.true_negative) += 1;
      }
    }
  }
  return out;
}

}  // namespace uavmot::eval::detail
