#include "sim_truth.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>

#include "split_merge.hpp"

namespace uavmot::tracking::testing {

TruthMeasurements::TruthMeasurements(TruthMeasurementOptions options) : options_(options), rng_(options.seed) {}

void TruthMeasurements::make(const sim::SimFrame& frame, MotionEstimate& motion, SegmentationResult& segmentation) {
  std::normal_distribution<double> n01(0.0, 1.0);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  motion = MotionEstimate{};
  segmentation = SegmentationResult{};
  motion.frame_index = segmentation.frame_index = frame.index;
  motion.homography = frame.homography_from_previous;
  motion.quality.valid = true;
  std::vector<const sim::ObjectTruth*> moving;
  for (const auto& o : frame.objects) {
    auto& uvs = feature_uv_[o.id];
    if (uvs.empty()) {
      for (int j = 0; j < options_.features_per_vehicle; ++j) uvs.emplace_back(0.9 * u01(rng_) - 0.45, 0.9 * u01(rng_) - 0.45);
    }
    if (o.visibility < options_.min_visibility) continue;
    for (size_t j = 0; j < uvs.size(); ++j) {
      TrackedFeature f;
      f.id = static_cast<uint64_t>(o.id) * 1000 + j;
      f.position = from_box_coordinates(o.box, uvs[j]) + cv::Point2d(n01(rng_), n01(rng_)) * options_.feature_position_noise_px;
      f.velocity = o.velocity_px + cv::Vec2d(n01(rng_), n01(rng_)) * options_.feature_velocity_noise;
      f.moving = o.moving;
      f.age = static_cast<uint32_t>(frame.index);
      motion.features.push_back(f);
    }
    if (o.moving) moving.push_back(&o);
  }
  std::vector<size_t> group(moving.size());
  std::iota(group.begin(), group.end(), 0);
  std::function<size_t(size_t)> root = [&](size_t x) { return group[x] == x ? x : group[x] = root(group[x]); };
  for (size_t a = 0; a < moving.size(); ++a) {
    for (size_t b = a + 1; b < moving.size(); ++b) {
      OrientedBox grown = moving[a]->box;
      grown.width += options_.merge_gap_px;
      grown.length += options_.merge_gap_px;
      if (intersection_area(grown, moving[b]->box) > 0.0) group[root(a)] = root(b);
    }
  }
  std::map<size_t, std::vector<OrientedBox>> members;
  for (size_t i = 0; i < moving.size(); ++i) members[root(i)].push_back(moving[i]->box);
  for (const auto& [r, boxes] : members) {
    if (u01(rng_) < options_.region_miss_probability) continue;
    if (boxes.size() > 1) ++merged_regions_;
    OrientedBox b = boxes.size() == 1 ? boxes.front() : enclosing_box(boxes);
    b.cx += n01(rng_) * options_.region_position_noise_px;
    b.cy += n01(rng_) * options_.region_position_noise_px;
    b.width = std::max(1.0, b.width + n01(rng_) * options_.region_size_noise_px);
    b.length = std::max(1.0, b.length + n01(rng_) * options_.region_size_noise_px);
    b.angle_deg = normalize_axis_angle_deg(b.angle_deg + n01(rng_) * options_.region_angle_noise_deg);
    Region region;
    region.box = b;
    segmentation.regions.push_back(region);
  }
}

void PaperScorer::add(const sim::SimFrame& frame, const std::vector<OrientedBox>& boxes, const std::vector<uint64_t>& ids) {
  const auto& truth = frame.objects;
  std::vector<std::vector<size_t>> boxes_of(truth.size());
  std::vector<std::vector<size_t>> truths_of(boxes.size());
  for (size_t t = 0; t < truth.size(); ++t) {
    for (size_t b = 0; b < boxes.size(); ++b) {
      if (intersection_area(truth[t].box, boxes[b]) > 0.3 * box_area(truth[t].box)) {
        boxes_of[t].push_back(b);
        truths_of[b].push_back(t);
      }
    }
  }
  for (size_t t = 0; t < truth.size(); ++t) {
    if (!truth[t].moving || truth[t].visibility < 0.99) continue;
    ++score_.instances;
    if (boxes_of[t].empty()) {
      ++score_.missed;
      continue;
    }
    if (boxes_of[t].size() > 1) {
      ++score_.over;
      continue;
    }
    const size_t b = boxes_of[t][0];
    const auto moving_covered = std::count_if(truths_of[b].begin(), truths_of[b].end(), [&](size_t o) { return truth[o].moving; });
    if (moving_covered > 1) {
      ++score_.under;
      continue;
    }
    ++score_.correct;
    score_.position_error += std::hypot(boxes[b].cx - truth[t].box.cx, boxes[b].cy - truth[t].box.cy);
    score_.width_error += std::abs(boxes[b].width - truth[t].box.width);
    score_.length_error += std::abs(boxes[b].length - truth[t].box.length);
    ++error_count_;
  }
  // Identities and false tracks: each box to the vehicle it overlaps most (IoU > 0.2).
  for (size_t b = 0; b < boxes.size(); ++b) {
    const sim::ObjectTruth* best = nullptr;
    double best_iou = 0.2;
    for (const auto& o : truth) {
      const double iou = intersection_over_union(o.box, boxes[b]);
      if (iou > best_iou) {
        best_iou = iou;
        best = &o;
      }
    }
    if (best == nullptr) {
      ++score_.false_track_frames;
      continue;
    }
    if (best->parked) ++score_.parked_track_frames;
    if (!best->moving || b >= ids.size()) continue;
    auto& seen = ids_of_vehicle_[best->id];
    if (seen.empty() || seen.back() != ids[b]) seen.push_back(ids[b]);
  }
}

PaperScore PaperScorer::result() const {
  PaperScore s = score_;
  if (error_count_ > 0) {
    s.position_error /= error_count_;
    s.width_error /= error_count_;
    s.length_error /= error_count_;
  }
  s.moving_vehicles_tracked = static_cast<int>(ids_of_vehicle_.size());
  for (const auto& [vehicle, ids] : ids_of_vehicle_) s.id_switches += static_cast<int>(ids.size()) - 1;
  return s;
}

PaperScore run_sim_truth(const std::string& preset, int frames, uint64_t seed, const TruthMeasurementOptions& measurements,
                         TrackerOptions options, int score_from) {
  sim::Scenario scenario = sim::preset_scenario(preset);
  scenario.frames = frames;
  scenario.sensor.write_video = false;
  sim::Simulator simulator(scenario, seed);
  options.image_width = scenario.camera.width;
  options.image_height = scenario.camera.height;
  Tracker tracker(options, simulator.scene());
  TruthMeasurements source(measurements);
  PaperScorer scorer;
  sim::SimFrame frame;
  MotionEstimate motion;
  SegmentationResult segmentation;
  while (simulator.next(frame)) {
    source.make(frame, motion, segmentation);
    const TrackList tracks = tracker.process(motion, segmentation);
    if (frame.index < score_from) continue;
    std::vector<OrientedBox> boxes;
    std::vector<uint64_t> ids;
    for (const auto& t : tracks.tracks) {
      if (t.state == TrackState::Tentative) continue;
      boxes.push_back(t.box);
      ids.push_back(t.id);
    }
    scorer.add(frame, boxes, ids);
  }
  return scorer.result();
}

}  // namespace uavmot::tracking::testing
