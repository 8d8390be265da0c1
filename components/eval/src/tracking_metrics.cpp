// CLEAR MOT, identity (IDF1) and HOTA, following TrackEval's implementations
// (trackeval/metrics/clear.py, identity.py, hota.py) step by step.
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "assignment.hpp"
#include "metrics.hpp"

namespace uavmot::eval::detail {
namespace {
constexpr double kEps = std::numeric_limits<double>::epsilon();

double box_iou(const PredictedBox& p, const GroundTruthObject& g, bool oriented) {
  if (oriented && p.oriented && g.oriented) return intersection_over_union(*p.oriented, g.box);
  const cv::Rect2d inter = p.bounds & g.bounds;
  const double i = inter.area();
  const double u = p.bounds.area() + g.bounds.area() - i;
  return u > 0.0 ? i / u : 0.0;
}

}  // namespace

TrackingData prepare_tracking(const Sequence& sequence, const Predictions& predictions, const EvalOptions& options,
                              const std::vector<int64_t>& frames, double distractor_threshold) {
  TrackingData data;
  std::map<int64_t, int> gt_index, tracker_index;
  for (const int64_t frame : frames) {
    TrackingFrame tf;
    static const std::vector<GroundTruthObject> no_objects;
    static const std::vector<PredictedBox> no_boxes;
    auto oit = sequence.objects.find(frame);
    auto bit = predictions.boxes.find(frame);
    const auto& objects = oit == sequence.objects.end() ? no_objects : oit->second;
    const auto& boxes = bit == predictions.boxes.end() ? no_boxes : bit->second;
    std::vector<const GroundTruthObject*> scored, ignored;
    for (const auto& o : objects) {
      if (is_scored(o, options)) scored.push_back(&o);
      else if (is_ignored(o, options)) ignored.push_back(&o);
    }
    std::vector<const PredictedBox*> tracked;
    for (const auto& b : boxes)
      if (b.id >= 0) tracked.push_back(&b);
    // Remove predictions matched to "don't care" objects (TrackEval's distractor step).
    if (!ignored.empty() && !tracked.empty()) {
      std::vector<const GroundTruthObject*> all = scored;
      all.insert(all.end(), ignored.begin(), ignored.end());
      std::vector<std::vector<double>> score(all.size(), std::vector<double>(tracked.size(), 0.0));
      for (size_t g = 0; g < all.size(); ++g)
        for (size_t t = 0; t < tracked.size(); ++t) {
          const double iou = box_iou(*tracked[t], *all[g], options.oriented_iou);
          score[g][t] = iou >= distractor_threshold - kEps ? iou : 0.0;
        }
      std::vector<char> drop(tracked.size(), 0);
      for (const auto& [g, t] : maximize_assignment(score))
        if (score[g][t] > kEps && static_cast<size_t>(g) >= scored.size()) drop[t] = 1;
      std::vector<const PredictedBox*> kept;
      for (size_t t = 0; t < tracked.size(); ++t)
        if (!drop[t]) kept.push_back(tracked[t]);
      tracked = kept;
    }
    for (const auto* o : scored) {
      auto it = gt_index.emplace(o->id, static_cast<int>(gt_index.size())).first;
      tf.gt_ids.push_back(it->second);
    }
    for (const auto* b : tracked) {
      auto it = tracker_index.emplace(b->id, static_cast<int>(tracker_index.size())).first;
      tf.tracker_ids.push_back(it->second);
    }
    tf.similarity.assign(scored.size(), std::vector<double>(tracked.size(), 0.0));
    for (size_t g = 0; g < scored.size(); ++g)
      for (size_t t = 0; t < tracked.size(); ++t) tf.similarity[g][t] = box_iou(*tracked[t], *scored[g], options.oriented_iou);
    data.gt_detections += static_cast<int64_t>(scored.size());
    data.tracker_detections += static_cast<int64_t>(tracked.size());
    data.frames.push_back(std::move(tf));
  }
  data.gt_id_count = static_cast<int>(gt_index.size());
  data.tracker_id_count = static_cast<int>(tracker_index.size());
  return data;
}

void clear_mot(const TrackingData& data, double threshold, ClearMot& out) {
  out.threshold = threshold;
  out.gt_detections = data.gt_detections;
  out.tracker_detections = data.tracker_detections;
  const int n_gt = data.gt_id_count;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<int64_t> gt_seen(n_gt, 0), gt_matched(n_gt, 0), gt_segments(n_gt, 0);
  std::vector<double> prev_tracker(n_gt, nan), prev_step_tracker(n_gt, nan);
  int64_t tp = 0, fn = 0, fp = 0, idsw = 0;
  double motp_sum = 0.0;
  for (const TrackingFrame& f : data.frames) {
    const size_t ng = f.gt_ids.size(), nt = f.tracker_ids.size();
    // As TrackEval: steps without ground truth or without predictions leave the
    // "tracked in the previous step" memory untouched.
    if (ng == 0) {
      fp += static_cast<int64_t>(nt);
      continue;
    }
    if (nt == 0) {
      fn += static_cast<int64_t>(ng);
      for (int g : f.gt_ids) ++gt_seen[g];
      continue;
    }
    std::vector<int> matched_gt, matched_tr;
    std::vector<double> matched_sim;
    {
      std::vector<std::vector<double>> score(ng, std::vector<double>(nt, 0.0));
      for (size_t g = 0; g < ng; ++g)
        for (size_t t = 0; t < nt; ++t) {
          const double sim = f.similarity[g][t];
          const bool continues = prev_step_tracker[f.gt_ids[g]] == static_cast<double>(f.tracker_ids[t]);
          score[g][t] = sim < threshold - kEps ? 0.0 : 1000.0 * continues + sim;
        }
      for (const auto& [g, t] : maximize_assignment(score)) {
        if (score[g][t] <= kEps) continue;
        matched_gt.push_back(f.gt_ids[g]);
        matched_tr.push_back(f.tracker_ids[t]);
        matched_sim.push_back(f.similarity[g][t]);
      }
    }
    for (size_t k = 0; k < matched_gt.size(); ++k) {
      const double before = prev_tracker[matched_gt[k]];
      if (!std::isnan(before) && before != static_cast<double>(matched_tr[k])) ++idsw;
      motp_sum += matched_sim[k];
    }
    for (int g : f.gt_ids) ++gt_seen[g];
    std::vector<char> was_tracked(n_gt, 0);
    for (int g = 0; g < n_gt; ++g) was_tracked[g] = !std::isnan(prev_step_tracker[g]);
    std::fill(prev_step_tracker.begin(), prev_step_tracker.end(), nan);
    for (size_t k = 0; k < matched_gt.size(); ++k) {
      ++gt_matched[matched_gt[k]];
      prev_tracker[matched_gt[k]] = matched_tr[k];
      prev_step_tracker[matched_gt[k]] = matched_tr[k];
      if (!was_tracked[matched_gt[k]]) ++gt_segments[matched_gt[k]];
    }
    tp += static_cast<int64_t>(matched_gt.size());
    fn += static_cast<int64_t>(ng - matched_gt.size());
    fp += static_cast<int64_t>(nt - matched_gt.size());
  }
  out.tp = tp;
  out.fn = fn;
  out.fp = fp;
  out.id_switches = idsw;
  out.gt_ids = n_gt;
  out.mostly_tracked = out.partially_tracked = out.mostly_lost = out.fragmentations = 0;
  for (int g = 0; g < n_gt; ++g) {
    if (gt_seen[g] == 0) continue;
    const double ratio = static_cast<double>(gt_matched[g]) / static_cast<double>(gt_seen[g]);
    if (ratio > 0.8) ++out.mostly_tracked;
    else if (ratio >= 0.2) ++out.partially_tracked;
    else ++out.mostly_lost;
    if (gt_segments[g] > 0) out.fragmentations += gt_segments[g] - 1;
  }
  const double n = std::max<double>(1.0, static_cast<double>(tp + fn));
  out.mota = static_cast<double>(tp - fp - idsw) / n;
  out.motp = tp > 0 ? motp_sum / static_cast<double>(tp) : 0.0;
}

void identity(const TrackingData& data, double threshold, ClearMot& out) {
  const int ng = data.gt_id_count, nt = data.tracker_id_count;
  out.idtp = 0;
  if (ng > 0 && nt > 0) {
    std::vector<std::vector<double>> matches(ng, std::vector<double>(nt, 0.0));
    for (const TrackingFrame& f : data.frames)
      for (size_t g = 0; g < f.gt_ids.size(); ++g)
        for (size_t t = 0; t < f.tracker_ids.size(); ++t)
          if (f.similarity[g][t] >= threshold - kEps) matches[f.gt_ids[g]][f.tracker_ids[t]] += 1.0;
    // The global one-to-one id mapping that maximises identity true positives.
    for (const auto& [g, t] : maximize_assignment(matches)) out.idtp += static_cast<int64_t>(matches[g][t]);
  }
  out.idfn = data.gt_detections - out.idtp;
  out.idfp = data.tracker_detections - out.idtp;
  const double denom = static_cast<double>(2 * out.idtp + out.idfn + out.idfp);
  out.idf1 = denom > 0 ? 2.0 * static_cast<double>(out.idtp) / denom : 0.0;
  out.idp = data.tracker_detections > 0 ? static_cast<double>(out.idtp) / static_cast<double>(data.tracker_detections) : 0.0;
  out.idr = data.gt_detections > 0 ? static_cast<double>(out.idtp) / static_cast<double>(data.gt_detections) : 0.0;
}

HotaSummary hota(const TrackingData& data, double alpha) {
  const int ng = data.gt_id_count, nt = data.tracker_id_count;
  HotaSummary out;
  // Global alignment: how well each gt id and tracker id overlap over the whole sequence.
  std::vector<std::vector<double>> potential(ng, std::vector<double>(nt, 0.0));
  std::vector<double> gt_count(ng, 0.0), tr_count(nt, 0.0);
  for (const TrackingFrame& f : data.frames) {
    const size_t g_n = f.gt_ids.size(), t_n = f.tracker_ids.size();
    std::vector<double> row_sum(g_n, 0.0), col_sum(t_n, 0.0);
    for (size_t g = 0; g < g_n; ++g)
      for (size_t t = 0; t < t_n; ++t) {
        row_sum[g] += f.similarity[g][t];
        col_sum[t] += f.similarity[g][t];
      }
    for (size_t g = 0; g < g_n; ++g)
      for (size_t t = 0; t < t_n; ++t) {
        const double denom = row_sum[g] + col_sum[t] - f.similarity[g][t];
        if (denom > kEps) potential[f.gt_ids[g]][f.tracker_ids[t]] += f.similarity[g][t] / denom;
      }
    for (int g : f.gt_ids) gt_count[g] += 1.0;
    for (int t : f.tracker_ids) tr_count[t] += 1.0;
  }
  std::vector<std::vector<double>> alignment(ng, std::vector<double>(nt, 0.0));
  for (int g = 0; g < ng; ++g)
    for (int t = 0; t < nt; ++t) alignment[g][t] = potential[g][t] / (gt_count[g] + tr_count[t] - potential[g][t]);

  std::vector<std::vector<double>> matches(ng, std::vector<double>(nt, 0.0));
  double tp = 0, fn = 0, fp = 0, loc = 0;
  for (const TrackingFrame& f : data.frames) {
    const size_t g_n = f.gt_ids.size(), t_n = f.tracker_ids.size();
    if (g_n == 0) {
      fp += static_cast<double>(t_n);
      continue;
    }
    if (t_n == 0) {
      fn += static_cast<double>(g_n);
      continue;
    }
    std::vector<std::vector<double>> score(g_n, std::vector<double>(t_n, 0.0));
    for (size_t g = 0; g < g_n; ++g)
      for (size_t t = 0; t < t_n; ++t) score[g][t] = alignment[f.gt_ids[g]][f.tracker_ids[t]] * f.similarity[g][t];
    int found = 0;
    for (const auto& [g, t] : maximize_assignment(score)) {
      if (f.similarity[g][t] < alpha - kEps) continue;
      ++found;
      loc += f.similarity[g][t];
      matches[f.gt_ids[g]][f.tracker_ids[t]] += 1.0;
    }
    tp += found;
    fn += static_cast<double>(g_n) - found;
    fp += static_cast<double>(t_n) - found;
  }
  double ass_sum = 0.0;
  for (int g = 0; g < ng; ++g)
    for (int t = 0; t < nt; ++t) {
      if (matches[g][t] == 0.0) continue;
      const double ass = matches[g][t] / std::max(1.0, gt_count[g] + tr_count[t] - matches[g][t]);
      ass_sum += matches[g][t] * ass;
    }
  out.assa = ass_sum / std::max(1.0, tp);
  out.deta = tp / std::max(1.0, tp + fn + fp);
  out.loca = std::max(1e-10, loc) / std::max(1e-10, tp);
  out.hota = std::sqrt(out.deta * out.assa);
  return out;
}

}  // namespace uavmot::eval::detail
