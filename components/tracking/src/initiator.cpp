#include "initiator.hpp"

#include <algorithm>
#include <limits>

#include "kalman_model.hpp"
#include "piece_merger.hpp"
#include "split_merge.hpp"
#include "uavmot/core/spatial_grid.hpp"

namespace uavmot::tracking {
namespace {

// Within the ratio, or within two region-size sigmas (a narrow box's width is noisy in relative terms).
bool similar_size(const OrientedBox& a, const OrientedBox& b, double ratio, double slack_px) {
  auto within = [ratio, slack_px](double x, double y) {
    return std::max(x, y) <= ratio * std::max(std::min(x, y), 1e-6) || std::abs(x - y) <= slack_px;
  };
  return within(a.length, b.length) && within(a.width, b.width);
}

// The track's last velocity and the region's motion must not point apart (a vehicle that left the view
// is not re-acquired by another one driving in where it left).
bool compatible_direction(const TrackRecord& track, const cv::Vec2d* region_velocity, double min_speed) {
  if (region_velocity == nullptr) return true;
  const cv::Vec2d last(track.mean[kVx], track.mean[kVy]);
  if (cv::norm(last) < min_speed || cv::norm(*region_velocity) < min_speed) return true;
  return last.dot(*region_velocity) > 0.0;
}

// Where and how alike a region must be to re-acquire a dormant track.
struct ReacquireGate {
  double radius_px;     // along the anchor's axis
  double lateral_px;    // across it
  double size_ratio;    // similar_size() ...
  double size_slack_px;  // ... or within this
  double min_speed_px;  // compatible_direction() compares directions above this speed
};

ReacquireGate reacquire_gate(const TrackerOptions& options, const SceneInfo& scene) {
  return {scene.metres_to_px(options.reacquire_radius_m), scene.metres_to_px(options.reacquire_lateral_m),
          options.reacquire_size_ratio, 2.0 * options.region_size_sigma_px, options.feature_min_speed_for_direction};
}

// The dormant track closest to `region` within the re-acquisition radius, or -1.
// Vehicles that stop and go move along their axis, so the gate is long along it and narrow across.
int find_dormant(const OrientedBox& region, const cv::Vec2d* region_velocity, const std::vector<TrackRecord>& dormant,
                 const ReacquireGate& gate) {
  int best = -1;
  double best_distance = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < dormant.size(); ++i) {
    const OrientedBox& anchor = dormant[i].anchor_box;
    const cv::Point2d uv = to_box_coordinates(anchor, {region.cx, region.cy});
    const double along = std::abs(uv.x * anchor.length);
    const double across = std::abs(uv.y * anchor.width);
    const double d = along + across;
    if (along <= gate.radius_px && across <= gate.lateral_px && d < best_distance &&
        similar_size(region, anchor, gate.size_ratio, gate.size_slack_px) &&
        compatible_direction(dormant[i], region_velocity, gate.min_speed_px)) {
      best = static_cast<int>(i);
      best_distance = d;
    }
  }
  return best;
}

// A blob less than half a vehicle right at the nose or tail of a confirmed moving track, in its lane
// (the piece rule), is part of that vehicle: a truck's cab or a windscreen, not a new vehicle.
bool part_of_a_live_vehicle(const OrientedBox& region, const std::vector<OrientedBox>& live_boxes,
                            const std::vector<TrackRecord>& live, const SpatialGrid& grid, const TrackerOptions& options,
                            const SceneInfo& scene) {
  if (!(options.piece_max_gap_m > 0.0)) return false;
  const double vehicle_area = scene.metres_to_px(scene.vehicle_length_m) * scene.metres_to_px(scene.vehicle_width_m);
  if (box_area(region) >= 0.5 * vehicle_area) return false;
  const double reach = scene.metres_to_px(2.0 * options.piece_max_gap_m + options.max_object_width_m);
  // The track's box often misses the end of the vehicle nearest the blob: allow twice the piece gap.
  TrackerOptions wider = options;
  wider.piece_max_gap_m = 2.0 * options.piece_max_gap_m;
  for (const int i : grid.query_near(axis_aligned_bounds(region), reach)) {
    const TrackRecord& t = live[static_cast<size_t>(i)];
    if (t.state == TrackState::Tentative) continue;
    const cv::Vec2d v(t.mean[kVx], t.mean[kVy]);
    if (are_pieces_of_one_object(live_boxes[static_cast<size_t>(i)], v, region, v, wider, scene)) return true;
  }
  return false;
}

}  // namespace

void initiate_tracks(const std::vector<int>& free_regions, const FrameInput& input,
                     const std::vector<OrientedBox>& live_boxes, const TrackerOptions& options, const SceneInfo& scene,
                     TrackerState& state) {
  const std::vector<OrientedBox>& regions = input.regions;
  const FeatureIndex& features = input.features;
  SpatialGrid live_grid;
  for (size_t i = 0; i < live_boxes.size(); ++i) live_grid.insert(static_cast<int>(i), axis_aligned_bounds(live_boxes[i]));
  std::vector<OrientedBox> started;  // boxes started in this call, so two overlapping regions start one track
  const BoxMeasurementNoise noise = box_measurement_noise(options);
  const ReacquireGate gate = reacquire_gate(options, scene);
  for (const int r : free_regions) {
    const OrientedBox& region = regions[static_cast<size_t>(r)];
    const double area = box_area(region);
    bool covered = false;
    for (const int i : live_grid.query(axis_aligned_bounds(region))) {
      covered = covered || intersection_area(region, live_boxes[static_cast<size_t>(i)]) > options.init_max_overlap_fraction * area;
    }
    for (const auto& s : started) covered = covered || intersection_area(region, s) > options.init_max_overlap_fraction * area;
    if (covered || part_of_a_live_vehicle(region, live_boxes, state.tracks, live_grid, options, scene)) continue;
    cv::Vec2d velocity(0.0, 0.0);
    const bool has_motion = region_motion(region, features, velocity);
    const KalmanState kalman = initial_state(
        region, velocity, has_motion ? options.init_velocity_sigma_features : options.init_velocity_sigma, noise);
    const int dormant = find_dormant(region, has_motion ? &velocity : nullptr, state.dormant, gate);
    TrackRecord track;
    if (dormant >= 0) {
      // Re-acquired: same id and history, fresh filter state, features relearnt.
      track = state.dormant[static_cast<size_t>(dormant)];
      state.dormant.erase(state.dormant.begin() + dormant);
      track.state = TrackState::Confirmed;
      track.frames_dormant = 0;
      track.features.clear();
    } else {
      track.id = state.next_id++;
      track.state = TrackState::Tentative;
      track.age = 0;
      track.hits = 0;
      track.hit_history = 0;
      track.origin = {region.cx, region.cy};
      track.travel_from = track.origin;
    }
    ++track.age;
    ++track.hits;
    track.hit_history = (track.hit_history << 1) | 1u;
    track.frames_since_update = 0;
    track.anchor_box = region;
    if (track.state == TrackState::Tentative && options.confirm_hits <= 1) track.state = TrackState::Confirmed;
    store(kalman, track);
    state.tracks.push_back(std::move(track));
    started.push_back(region);
  }
}

}  // namespace uavmot::tracking
