#include <fmt/format.h>

#include "uavmot/eval/evaluate.hpp"

namespace uavmot::eval {

namespace {
// "<10", "10-20", ">=20".
std::string band_name(const SizeBand& b) {
  if (b.min_length_px <= 0.0) return fmt::format("<{:g}", b.max_length_px);
  if (b.max_length_px <= 0.0) return fmt::format(">={:g}", b.min_length_px);
  return fmt::format("{:g}-{:g}", b.min_length_px, b.max_length_px);
}
}  // namespace

std::string format_table(const EvaluationResult& r) {
  std::string out;
  const auto pct = [](double v) { return fmt::format("{:6.1f} %", 100.0 * v); };
  out += fmt::format("Sequence {}: {} frames scored, {}x{} px, GSD {} m/px\n\n", r.sequence.name, r.frames, r.sequence.width,
                     r.sequence.height, r.sequence.gsd_m > 0 ? fmt::format("{:g}", r.sequence.gsd_m) : std::string("unknown"));
  const Completeness& c = r.completeness;
  out += fmt::format("Completeness (paper Table I), {} moving-object instances\n", c.instances);
  out += fmt::format("  correct          {:>8}  {}\n", c.correct, pct(c.rate(c.correct)));
  out += fmt::format("  under-segmented  {:>8}  {}\n", c.under_segmented, pct(c.rate(c.under_segmented)));
  out += fmt::format("  over-segmented   {:>8}  {}\n", c.over_segmented, pct(c.rate(c.over_segmented)));
  out += fmt::format("  missed           {:>8}  {}\n", c.missed, pct(c.rate(c.missed)));
  out += "  by length in the image:\n";
  for (const SizeBand& b : c.by_length) {
    if (b.instances == 0) continue;
    out += fmt::format("    {:>6} px {:>8} instances, correct {}, missed {}\n", band_name(b), b.instances,
                       pct(b.correct_rate()), pct(b.rate(b.missed)));
  }
  out += "\n";
  const Precision& p = r.precision;
  out += fmt::format("Precision (paper Table II), mean absolute error over {} correct instances ({} boxes)\n", p.samples,
                     p.oriented ? "oriented" : "axis-aligned");
  out += fmt::format("             e_x      e_y      e_w      e_l\n");
  out += fmt::format("  px    {:8.2f} {:8.2f} {:8.2f} {:8.2f}\n", p.error_x_px, p.error_y_px, p.error_width_px, p.error_length_px);
  if (r.sequence.gsd_m > 0)
    out += fmt::format("  m     {:8.2f} {:8.2f} {:8.2f} {:8.2f}\n", p.error_x_m, p.error_y_m, p.error_width_m, p.error_length_m);
  const FalseAlarms& f = r.false_alarms;
  out += fmt::format("\nFalse alarms: {} of {} boxes ({:.2f} per frame), {} on parked vehicles; {} boxes on stopped vehicles not scored\n",
                     f.false_alarms, f.boxes, f.per_frame(), f.on_parked, f.on_stopped);
  if (f.structures_known)
    out += fmt::format("  on static structures: {} ({:.3f} per frame): {} on buildings, {} on trees, {} on walls\n", f.on_structure,
                       f.on_structure_per_frame(), f.on_building, f.on_tree, f.on_wall);
  if (r.has_identities) {
    out += "\nTracking (TrackEval definitions)\n";
    out += "  IoU    MOTA    MOTP    IDF1    HOTA    DetA    AssA      FP      FN  IDSW  Frag   MT   PT   ML\n";
    for (const ClearMot& m : r.tracking)
      out += fmt::format("  {:.2f} {:7.3f} {:7.3f} {:7.3f} {:7.3f} {:7.3f} {:7.3f} {:7} {:7} {:5} {:5} {:4} {:4} {:4}\n", m.threshold,
                         m.mota, m.motp, m.idf1, m.hota, m.deta, m.assa, m.fp, m.fn, m.id_switches, m.fragmentations,
                         m.mostly_tracked, m.partially_tracked, m.mostly_lost);
    if (r.hota_averaged)
      out += fmt::format("  HOTA averaged over IoU 0.05..0.95: HOTA {:.3f}  DetA {:.3f}  AssA {:.3f}  LocA {:.3f}\n",
                         r.hota_averaged->hota, r.hota_averaged->deta, r.hota_averaged->assa, r.hota_averaged->loca);
  } else {
    out += "\nTracking: no track ids in the predictions (boxes with id -1), CLEAR MOT / IDF1 / HOTA skipped\n";
  }
  if (r.homography) {
    const HomographyErrors& h = *r.homography;
    out += fmt::format("\nHomography transfer error over {} frames ({} missing): mean {:.3f} px, p95 {:.3f} px, max {:.3f} px (worst frame {})\n",
                       h.frames, h.missing, h.mean_px, h.p95_px, h.max_px, h.worst_frame);
  }
  if (r.features) {
    const FeatureClassification& fc = *r.features;
    out += fmt::format("\nMoving-feature classification over {} features ({} ambiguous near edges): precision {:.3f}, recall {:.3f} "
                       "(TP {}, FP {}, FN {}, TN {})\n",
                       fc.features, fc.ambiguous, fc.precision(), fc.recall(), fc.true_positive, fc.false_positive,
                       fc.false_negative, fc.true_negative);
  }
  return out;
}

nlohmann::ordered_json to_json(const EvaluationResult& r) {
  nlohmann::ordered_json j;
  j["sequence"] = {{"name", r.sequence.name}, {"length", r.sequence.length}, {"width", r.sequence.width},
                   {"height", r.sequence.height}, {"fps", r.sequence.fps}, {"gsd_m", r.sequence.gsd_m}};
  j["frames_scored"] = r.frames;
  const Completeness& c = r.completeness;
  j["completeness"] = {{"instances", c.instances}, {"correct", c.correct}, {"under_segmented", c.under_segmented},
                       {"over_segmented", c.over_segmented}, {"missed", c.missed}, {"correct_rate", c.rate(c.correct)},
                       {"under_segmented_rate", c.rate(c.under_segmented)}, {"over_segmented_rate", c.rate(c.over_segmented)},
                       {"missed_rate", c.rate(c.missed)}};
  nlohmann::ordered_json bands = nlohmann::ordered_json::array();
  for (const SizeBand& b : c.by_length) {
    bands.push_back({{"band", band_name(b)}, {"min_length_px", b.min_length_px},
                     {"max_length_px", b.max_length_px > 0.0 ? nlohmann::ordered_json(b.max_length_px) : nlohmann::ordered_json()},
                     {"instances", b.instances}, {"correct", b.correct}, {"missed", b.missed}, {"correct_rate", b.correct_rate()}});
  }
  j["completeness"]["by_length_px"] = bands;
  const Precision& p = r.precision;
  j["precision"] = {{"samples", p.samples}, {"oriented", p.oriented}, {"error_x_px", p.error_x_px}, {"error_y_px", p.error_y_px},
                    {"error_width_px", p.error_width_px}, {"error_length_px", p.error_length_px}, {"error_x_m", p.error_x_m},
                    {"error_y_m", p.error_y_m}, {"error_width_m", p.error_width_m}, {"error_length_m", p.error_length_m}};
  const FalseAlarms& f = r.false_alarms;
  j["false_alarms"] = {{"boxes", f.boxes}, {"false_alarms", f.false_alarms}, {"on_parked", f.on_parked},
                       {"on_stopped_not_scored", f.on_stopped}, {"per_frame", f.per_frame()}};
  if (f.structures_known) {
    j["false_alarms"]["on_structure"] = f.on_structure;
    j["false_alarms"]["on_structure_per_frame"] = f.on_structure_per_frame();
    j["false_alarms"]["on_structure_by_kind"] = {{"building", f.on_building}, {"tree", f.on_tree}, {"wall", f.on_wall}};
  }
  j["tracking"] = nlohmann::ordered_json::array();
  for (const ClearMot& m : r.tracking) {
    j["tracking"].push_back({{"iou_threshold", m.threshold}, {"MOTA", m.mota}, {"MOTP", m.motp}, {"TP", m.tp}, {"FP", m.fp},
                             {"FN", m.fn}, {"IDSW", m.id_switches}, {"Frag", m.fragmentations}, {"GT_IDs", m.gt_ids},
                             {"MT", m.mostly_tracked}, {"PT", m.partially_tracked}, {"ML", m.mostly_lost},
                             {"GT_Dets", m.gt_detections}, {"Dets", m.tracker_detections}, {"IDF1", m.idf1}, {"IDP", m.idp},
                             {"IDR", m.idr}, {"IDTP", m.idtp}, {"IDFP", m.idfp}, {"IDFN", m.idfn}, {"HOTA", m.hota},
                             {"DetA", m.deta}, {"AssA", m.assa}, {"LocA", m.loca}});
  }
  if (r.hota_averaged)
    j["hota_averaged"] = {{"HOTA", r.hota_averaged->hota}, {"DetA", r.hota_averaged->deta}, {"AssA", r.hota_averaged->assa},
                          {"LocA", r.hota_averaged->loca}};
  if (r.homography) {
    const HomographyErrors& h = *r.homography;
    j["homography"] = {{"frames", h.frames}, {"missing", h.missing}, {"mean_px", h.mean_px}, {"p95_px", h.p95_px},
                       {"max_px", h.max_px}, {"worst_frame", h.worst_frame}, {"worst_frame_mean_px", h.worst_frame_mean_px}};
  }
  if (r.features) {
    const FeatureClassification& fc = *r.features;
    j["features"] = {{"features", fc.features}, {"precision", fc.precision()}, {"recall", fc.recall()},
                     {"true_positive", fc.true_positive}, {"false_positive", fc.false_positive},
                     {"false_negative", fc.false_negative}, {"true_negative", fc.true_negative}, {"ambiguous", fc.ambiguous},
                     {"frames_without_mask", fc.frames_without_mask}};
  }
  return j;
}

}  // namespace uavmot::eval
