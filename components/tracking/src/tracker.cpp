#include "uavmot/tracking/tracker.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "frame_input.hpp"
#include "kalman_model.hpp"
#include "record_places.hpp"
#include "stages.hpp"
#include "uavmot/core/error.hpp"

namespace uavmot::tracking {
namespace {

Track to_output(const TrackRecord& record) {
  const KalmanState k = to_kalman(record);
  Track t;
  t.id = record.id;
  t.state = record.state;
  t.box = box_of(k.mean);
  t.velocity = velocity_of(k.mean);
  round_to_float32(t);  // output only: the Kalman state keeps its doubles
  t.sigma_x = std::sqrt(std::max(0.0, k.covariance(kX, kX)));
  t.sigma_y = std::sqrt(std::max(0.0, k.covariance(kY, kY)));
  t.sigma_width = std::sqrt(std::max(0.0, k.covariance(kWidth, kWidth)));
  t.sigma_length = std::sqrt(std::max(0.0, k.covariance(kLength, kLength)));
  t.sigma_angle_deg = std::sqrt(std::max(0.0, k.covariance(kAngle, kAngle)));
  t.age = record.age;
  t.frames_since_update = record.frames_since_update;
  for (const auto& link : record.features) t.feature_ids.push_back(link.feature_id);
  return t;
}

bool by_id(const TrackRecord& a, const TrackRecord& b) { return a.id < b.id; }

// Every live track predicted into this frame; its remembered places are carried through the homography too.
std::vector<TrackInFrame> predict_tracks(std::vector<TrackRecord> records, const Homography& h, const MotionModel& model) {
  std::vector<TrackInFrame> tracks;
  tracks.reserve(records.size());
  for (auto& r : records) {
    const KalmanState prior = model.predict(to_kalman(r), h);
    if (!is_finite(prior)) continue;  // cannot happen with validated input; drop rather than spread NaN
    carry_places(r, h);
    tracks.push_back(predicted_track(std::move(r), prior));
  }
  return tracks;
}

}  // namespace

Tracker::Tracker(TrackerOptions options, SceneInfo scene) : options_(std::move(options)), scene_(scene) {
  validate(options_);
  if (!(scene_.gsd_m > 0.0) || !std::isfinite(scene_.gsd_m)) throw InvalidArgument("scene.gsd_m must be positive");
  stages_ = std::make_shared<const TrackerStages>(make_stages(options_, scene_));
}

TrackList Tracker::process(const MotionEstimate& motion, const SegmentationResult& segmentation) {
  const TrackerStages& stage = *stages_;
  ++state_.frames_processed;
  const FrameInput in = read_frame_input(motion, segmentation, options_, scene_, state_);

  // 1. Predict every track with the camera motion as control input.
  std::vector<TrackInFrame> tracks = predict_tracks(std::move(state_.tracks), in.homography, *stage.motion_model);
  state_.tracks.clear();
  stage.deleter->age_dormant(state_, in.homography);
  // 2. Drop feature links that vanished or became outliers.
  stage.feature_associator->prune(tracks, in.features);
  // 3. Regions to tracks, 4. split and merge handling.
  const RegionAssociation gating = stage.region_associator->associate(in.regions, tracks);
  const std::vector<int> free_regions = stage.split_merge->resolve(gating, in, tracks);
  // 5. Kalman update; then the pieces of one long vehicle become one track (paper IV-C).
  for (auto& t : tracks) stage.updater->update(t, in.features);
  stage.split_merge->merge_pieces(tracks, in.features);
  for (auto& t : tracks) stage.updater->commit(t, in.features);
  // 6. Link new features (not during a merge, where the box is only reconstructed).
  stage.feature_associator->link(tracks, in.features);
  // 7. Lifecycle.
  std::vector<OrientedBox> live_boxes;
  for (auto& t : tracks) {
    if (t.absorbed) continue;  // a piece of another track's object
    switch (stage.deleter->judge(t, in)) {
      case Fate::Keep:
        live_boxes.push_back(t.posterior);
        state_.tracks.push_back(std::move(t.record));
        break;
      case Fate::Dormant:
        t.record.features.clear();
        t.record.frames_dormant = 0;
        state_.dormant.push_back(std::move(t.record));
        break;
      case Fate::Delete:
        break;
    }
  }
  std::sort(state_.dormant.begin(), state_.dormant.end(), by_id);
  // 8. New tracks from free regions.
  stage.initiator->initiate(free_regions, in, live_boxes, state_);
  std::sort(state_.tracks.begin(), state_.tracks.end(), by_id);

  TrackList out;
  out.stream_id = motion.stream_id;
  out.frame_index = motion.frame_index;
  out.capture_time_ns = motion.capture_time_ns;
  for (const auto& t : state_.tracks) out.tracks.push_back(to_output(t));
  return out;
}

void Tracker::restore(const TrackerState& state) {
  auto check = [](const TrackRecord& t) {
    const KalmanState k = to_kalman(t);
    const bool points_finite = std::isfinite(t.origin.x) && std::isfinite(t.origin.y) &&
                               std::isfinite(t.travel_from.x) && std::isfinite(t.travel_from.y);
    if (!is_finite(k) || t.id == 0 || !points_finite) throw InvalidArgument("tracker state: track " + std::to_string(t.id) + " is not valid");
  };
  // Counters the next frame increments: one at its limit (a corrupt or hostile sample) cannot go
  // on; frames_processed would overflow (found by fuzzing) and next_id would hand out id 0.
  if (state.frames_processed < 0 || state.frames_processed == std::numeric_limits<int64_t>::max()) {
    throw InvalidArgument("tracker state: frames_processed " + std::to_string(state.frames_processed) + " is out of range");
  }
  if (state.next_id == 0 || state.next_id == std::numeric_limits<uint64_t>::max()) {
    throw InvalidArgument("tracker state: next_id " + std::to_string(state.next_id) + " is out of range");
  }
  for (const auto& t : state.tracks) check(t);
  for (const auto& t : state.dormant) check(t);
  for (const auto* list : {&state.tracks, &state.dormant}) {
    for (const auto& t : *list) {
      if (t.id >= state.next_id) throw InvalidArgument("tracker state: track id " + std::to_string(t.id) + " >= next_id");
    }
  }
  state_ = state;
  std::sort(state_.tracks.begin(), state_.tracks.end(), by_id);
  std::sort(state_.dormant.begin(), state_.dormant.end(), by_id);
}

double speed_mps(const Track& track, const SceneInfo& scene) { return scene.speed_mps(cv::norm(track.velocity)); }
double speed_kmh(const Track& track, const SceneInfo& scene) { return 3.6 * speed_mps(track, scene); }

}  // namespace uavmot::tracking
