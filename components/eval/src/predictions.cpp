#include "uavmot/eval/predictions.hpp"

#include <set>

#include "text_records.hpp"
#include "uavmot/core/error.hpp"

namespace uavmot::eval {
namespace {
using detail::fail;
using detail::parse_integer;
using detail::parse_number;

void check_frame(const std::string& file, const detail::Record& r, int64_t frame, const SequenceInfo& info) {
  if (frame < 1 || frame > info.length)
    fail(file, r.line, "frame " + std::to_string(frame) + " is outside the sequence (1.." + std::to_string(info.length) + ")");
}

void load_tracks(const std::string& file, const SequenceInfo& info, Predictions& out) {
  std::set<std::pair<int64_t, int64_t>> seen;
  for (const auto& r : detail::read_records(file)) {
    if (r.fields.size() < 6 || r.fields.size() > 10)
      fail(file, r.line, "expected a MOTChallenge line: frame,id,bb_left,bb_top,bb_width,bb_height,conf,-1,-1,-1");
    const int64_t frame = parse_integer(file, r, 0, "frame");
    check_frame(file, r, frame, info);
    PredictedBox box;
    box.id = parse_integer(file, r, 1, "id");
    box.bounds = {parse_number(file, r, 2, "bb_left"), parse_number(file, r, 3, "bb_top"), parse_number(file, r, 4, "bb_width"),
                  parse_number(file, r, 5, "bb_height")};
    if (r.fields.size() > 6) box.confidence = parse_number(file, r, 6, "conf");
    if (!(box.bounds.width > 0.0 && box.bounds.height > 0.0)) fail(file, r.line, "bb_width and bb_height must be positive");
    if (box.id < -1 || box.id == 0) fail(file, r.line, "track ids start at 1 (-1 marks a box without identity)");
    if (box.id > 0 && !seen.insert({frame, box.id}).second)
      fail(file, r.line, "track " + std::to_string(box.id) + " appears twice in frame " + std::to_string(frame));
    out.boxes[frame].push_back(box);
  }
}

bool confirmed_state(const std::string& state) { return state == "confirmed" || state == "1"; }

void load_oriented(const std::string& file, const SequenceInfo& info, bool attach_only, Predictions& out) {
  const auto records = detail::read_records(file);
  if (records.empty()) return;
  const auto col = detail::header_columns(file, records[0], {"frame", "id", "cx", "cy", "width", "length", "angle_deg"});
  const bool has_state = col.count("state") > 0;
  std::set<std::pair<int64_t, int64_t>> seen;
  for (size_t i = 1; i < records.size(); ++i) {
    const auto& r = records[i];
    const int64_t frame = parse_integer(file, r, col.at("frame"), "frame");
    check_frame(file, r, frame, info);
    const int64_t id = parse_integer(file, r, col.at("id"), "id");
    OrientedBox box{parse_number(file, r, col.at("cx"), "cx"), parse_number(file, r, col.at("cy"), "cy"),
                    parse_number(file, r, col.at("width"), "width"), parse_number(file, r, col.at("length"), "length"),
                    parse_number(file, r, col.at("angle_deg"), "angle_deg")};
    if (!(box.width > 0.0 && box.length > 0.0)) fail(file, r.line, "width and length must be positive");
    if (id > 0 && !seen.insert({frame, id}).second)
      fail(file, r.line, "track " + std::to_string(id) + " appears twice in frame " + std::to_string(frame));
    if (attach_only) {
      // Give the oriented box to the tracks.txt box of the same frame and id.
      auto it = out.boxes.find(frame);
      if (it == out.boxes.end()) continue;
      for (PredictedBox& p : it->second)
        if (p.id == id) p.oriented = box;
      continue;
    }
    if (has_state && !confirmed_state(r.fields.at(col.at("state")))) continue;
    PredictedBox p;
    p.id = id;
    p.oriented = box;
    p.bounds = axis_aligned_bounds(box);
    out.boxes[frame].push_back(p);
  }
}

void load_features(const std::string& file, const SequenceInfo& info, Predictions& out) {
  const auto records = detail::read_records(file);
  if (records.empty()) return;
  const auto col = detail::header_columns(file, records[0], {"frame", "feature_id", "x", "y", "vx", "vy", "moving"});
  for (size_t i = 1; i < records.size(); ++i) {
    const auto& r = records[i];
    const int64_t frame = parse_integer(file, r, col.at("frame"), "frame");
    check_frame(file, r, frame, info);
    PredictedFeature f;
    const int64_t id = parse_integer(file, r, col.at("feature_id"), "feature_id");
    if (id < 0) fail(file, r.line, "feature_id must not be negative");
    f.id = static_cast<uint64_t>(id);
    f.position = {parse_number(file, r, col.at("x"), "x"), parse_number(file, r, col.at("y"), "y")};
    f.velocity = {parse_number(file, r, col.at("vx"), "vx"), parse_number(file, r, col.at("vy"), "vy")};
    const int64_t moving = parse_integer(file, r, col.at("moving"), "moving");
    if (moving != 0 && moving != 1) fail(file, r.line, "moving must be 0 or 1");
    f.moving = moving == 1;
    out.features[frame].push_back(f);
  }
}

}  // namespace

void Predictions::add_tracks(const TrackList& tracks, bool include_unconfirmed) {
  auto& frame_boxes = boxes[tracks.frame_index];
  for (const Track& t : tracks.tracks) {
    if (!include_unconfirmed && t.state != TrackState::Confirmed) continue;
    PredictedBox p;
    p.id = static_cast<int64_t>(t.id);
    p.oriented = t.box;
    p.bounds = axis_aligned_bounds(t.box);
    frame_boxes.push_back(p);
  }
}

void Predictions::add_boxes(int64_t frame, const std::vector<OrientedBox>& list) {
  auto& frame_boxes = boxes[frame];
  for (const OrientedBox& b : list) {
    PredictedBox p;
    p.id = -1;
    p.oriented = b;
    p.bounds = axis_aligned_bounds(b);
    frame_boxes.push_back(p);
  }
}

void Predictions::add_regions(const SegmentationResult& segmentation, SegmentationMethod method) {
  std::vector<OrientedBox> list;
  for (const Region& r : segmentation.regions)
    if (r.method == method) list.push_back(r.box);
  add_boxes(segmentation.frame_index, list);
}

void Predictions::add_clusters(const SegmentationResult& segmentation) {
  std::vector<OrientedBox> list;
  for (const FeatureCluster& c : segmentation.clusters) list.push_back(c.box);
  add_boxes(segmentation.frame_index, list);
}

void Predictions::add_motion(const MotionEstimate& motion) {
  if (motion.quality.valid) homographies[motion.frame_index] = motion.homography;
  auto& list = features[motion.frame_index];
  for (const TrackedFeature& f : motion.features) list.push_back({f.id, f.position, f.velocity, f.moving});
}

bool Predictions::has_identities() const {
  for (const auto& [frame, list] : boxes)
    for (const PredictedBox& b : list)
      if (b.id >= 0) return true;
  return false;
}

Predictions load_predictions(const PredictionFiles& files, const SequenceInfo& info) {
  Predictions out;
  if (files.tracks.empty() && files.oriented.empty()) throw InputError("no predictions given: need a tracks file or an oriented-box file");
  if (!files.tracks.empty()) load_tracks(files.tracks, info, out);
  if (!files.oriented.empty()) load_oriented(files.oriented, info, !files.tracks.empty(), out);
  if (!files.homographies.empty()) out.homographies = detail::read_homographies(files.homographies, info.length);
  if (!files.features.empty()) load_features(files.features, info, out);
  return out;
}

}  // namespace uavmot::eval
