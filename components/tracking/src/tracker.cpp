#include "uavmot/tracking/tracker.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "uavmot/core/error.hpp"
#include "uavmot/tracking/deleter.hpp"
#include "uavmot/tracking/feature_associator.hpp"
#include "uavmot/tracking/initiator.hpp"
#include "uavmot/tracking/kalman_model.hpp"
#include "uavmot/tracking/piece_merger.hpp"
#include "uavmot/tracking/predictor.hpp"
#include "uavmot/tracking/region_associator.hpp"
#include "uavmot/tracking/split_merge.hpp"
#include "uavmot/tracking/updater.hpp"

namespace uavmot::tracking {
namespace {

// Homographies this far from a similarity are treated as broken input rather than camera motion.
constexpr double kMinDeterminant = 1e-3;
constexpr double kMaxDeterminant = 1e3;

bool usable_homography(Homography& h) {
  if (!uavmot::is_finite(h) || !normalize_homography(h)) return false;
  const double det = cv::determinant(h);
  return std::isfinite(det) && std::abs(det) > kMinDeterminant && std::abs(det) < kMaxDeterminant;
}

bool method_selected(const std::string& choice, SegmentationMethod method, bool frame_has_fusion) {
  if (choice == "all") return true;
  if (choice == "auto") return !frame_has_fusion || method == SegmentationMethod::Fusion;
  return choice == to_string(method);
}

std::vector<OrientedBox> select_regions(const SegmentationResult& segmentation, const TrackerOptions& options,
                                        uint64_t& rejected) {
  const bool has_fusion = std::any_of(segmentation.regions.begin(), segmentation.regions.end(),
                                      [](const Region& r) { return r.method == SegmentationMethod::Fusion; });
  std::vector<OrientedBox> out;
  for (const auto& region : segmentation.regions) {
    if (!method_selected(options.region_method, region.method, has_fusion)) continue;
    const OrientedBox& b = region.box;
    if (!uavmot::is_finite(b) || b.width <= 0.0 || b.length <= 0.0) {
      ++rejected;
      continue;
    }
    if (box_area(b) < options.min_region_area_px) continue;
    OrientedBox normalized = b;
    normalized.angle_deg = normalize_axis_angle_deg(b.angle_deg);
    if (normalized.width > normalized.length) {  // keep the convention: length is the longer side
      std::swap(normalized.width, normalized.length);
      normalized.angle_deg = normalize_axis_angle_deg(normalized.angle_deg + 90.0);
    }
    out.push_back(normalized);
  }
  return out;
}

// This frame's valid features: the moving ones, and the stopped ones that a track links to (a link
// made while they moved).
FeatureIndex select_features(const MotionEstimate& motion, const std::vector<TrackRecord>& tracks,
                             const TrackerOptions& options, uint64_t& rejected) {
  std::vector<uint64_t> linked;
  if (options.stopped_link_min_frames > 0) {
    for (const auto& t : tracks) {
      for (const auto& link : t.features) linked.push_back(link.feature_id);
    }
    std::sort(linked.begin(), linked.end());
  }
  std::vector<TrackedFeature> moving;
  std::vector<TrackedFeature> stopped;
  for (const auto& f : motion.features) {
    if (!std::isfinite(f.position.x) || !std::isfinite(f.position.y) || !std::isfinite(f.velocity[0]) ||
        !std::isfinite(f.velocity[1])) {
      if (f.moving) ++rejected;
      continue;
    }
    if (f.moving) {
      moving.push_back(f);
    } else if (std::binary_search(linked.begin(), linked.end(), f.id)) {
      stopped.push_back(f);
    }
  }
  return FeatureIndex(std::move(moving), std::move(stopped), static_cast<uint32_t>(options.stopped_link_min_frames));
}

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

// The linked features' own motion: their median velocity updates the track's velocity and, for a
// vehicle under way, its direction names the box's axis. Returns that heading (deg), if any.
std::optional<double> update_with_feature_motion(KalmanState& kalman, const std::vector<const TrackedFeature*>& linked,
                                                 const TrackerOptions& options) {
  const auto velocity = median_velocity_of(linked, options.min_reconstruction_features);
  if (!velocity) return std::nullopt;
  if (options.feature_velocity_sigma_px > 0.0) {
    kalman = update_with_velocity(kalman, *velocity, options.feature_velocity_sigma_px);
  }
  if (!(options.heading_sigma_deg > 0.0) || cv::norm(*velocity) < options.heading_min_speed_px) return std::nullopt;
  const double heading = std::atan2((*velocity)[1], (*velocity)[0]) * 180.0 / M_PI;
  kalman = update_with_heading(kalman, heading, options.heading_sigma_deg);
  return heading;
}

// A track's velocity is observed once it has two region hits; before that it is a guess.
bool velocity_known(const TrackRecord& t) { return t.hits >= 2; }

}  // namespace

Tracker::Tracker(TrackerOptions options, SceneInfo scene) : options_(std::move(options)), scene_(scene) {
  validate(options_);
  if (!(scene_.gsd_m > 0.0) || !std::isfinite(scene_.gsd_m)) throw InvalidArgument("scene.gsd_m must be positive");
}

TrackList Tracker::process(const MotionEstimate& motion, const SegmentationResult& segmentation) {
  TrackList out;
  out.stream_id = motion.stream_id;
  out.frame_index = motion.frame_index;
  out.capture_time_ns = motion.capture_time_ns;
  ++state_.frames_processed;

  Homography h = motion.homography;
  if (!usable_homography(h)) {
    ++state_.rejected_homographies;
    h = identity_homography();
  }
  const std::vector<OrientedBox> regions = select_regions(segmentation, options_, state_.rejected_regions);
  const FeatureIndex features = select_features(motion, state_.tracks, options_, state_.rejected_features);

  // 1. Predict every track with the camera motion as control input.
  const ProcessNoise noise = process_noise(options_);
  std::vector<KalmanState> kalman;
  std::vector<TrackRecord> tracks;
  for (auto& t : state_.tracks) {
    KalmanState k = predict(to_kalman(t), h, noise);
    if (!is_finite(k)) continue;  // cannot happen with validated input; drop rather than spread NaN
    t.anchor_box = transform_box(h, t.anchor_box);
    kalman.push_back(k);
    tracks.push_back(std::move(t));
  }
  state_.tracks = std::move(tracks);
  age_dormant(state_, h, options_);
  const size_t n = state_.tracks.size();
  std::vector<OrientedBox> predicted(n);
  std::vector<cv::Vec2d> velocities(n);
  std::vector<bool> known(n);
  for (size_t i = 0; i < n; ++i) {
    predicted[i] = box_of(kalman[i].mean);
    velocities[i] = velocity_of(kalman[i].mean);
    known[i] = velocity_known(state_.tracks[i]);
  }

  // 2. Drop feature links that vanished or became outliers.
  for (size_t i = 0; i < n; ++i) {
    prune_feature_links(state_.tracks[i], predicted[i], velocities[i], known[i], features, options_);
  }

  // 3. Regions to tracks, 4. split and merge handling.
  const RegionAssociation association = associate_regions(regions, predicted, options_.min_intersection_fraction);
  const cv::Size2d max_object_size(scene_.metres_to_px(scene_.vehicle_width_m) * options_.single_object_size_factor,
                                   scene_.metres_to_px(scene_.vehicle_length_m) * options_.single_object_size_factor);
  const double confirm_min_speed_px = scene_.fps > 0.0 ? scene_.metres_to_px(options_.confirm_min_speed_mps) / scene_.fps : 0.0;
  const cv::Size2d largest_object(scene_.metres_to_px(options_.max_object_width_m),
                                  scene_.metres_to_px(scene_.vehicle_length_m) * options_.max_object_length_factor);
  const SplitMergeResult resolved = resolve_split_merge(association, regions, state_.tracks, predicted, velocities,
                                                        max_object_size, features, options_, largest_object);

  // 5. Kalman update; a track without a region may be carried by its features alone.
  const double vehicle_length_px = scene_.metres_to_px(scene_.vehicle_length_m);
  const BoxMeasurementNoise box_noise = box_measurement_noise(options_);
  std::vector<bool> region_hit(n, false);
  std::vector<bool> supported(n, false);
  std::vector<bool> may_link(n, false);
  for (size_t i = 0; i < n; ++i) {
    const TrackMeasurement& m = resolved.measurements[i];
    const std::vector<const TrackedFeature*> linked = linked_features(state_.tracks[i], features);
    const std::optional<double> heading = update_with_feature_motion(kalman[i], linked, options_);
    if (m.kind == MeasurementKind::Box) {
      OrientedBox box = heading ? box_along_heading(m.box, *heading) : m.box;
      // A heading means at least min_reconstruction_features linked features are present.
      if (heading && options_.feature_span_margin_px >= 0.0) {
        std::vector<cv::Point2d> points;
        for (const TrackedFeature* f : linked) points.push_back(f->position);
        box = lengthen_to_cover(box, points, options_.feature_span_margin_px, vehicle_length_px);
      }
      if (m.size_jump) open_size_uncertainty(kalman[i], box);
      kalman[i] = update_with_box(kalman[i], box, box_noise, options_.min_box_size_px);
      region_hit[i] = true;
      may_link[i] = true;
    } else if (m.kind == MeasurementKind::Centre) {
      kalman[i] = update_with_position(kalman[i], m.centre, options_.reconstruction_sigma_px);
      supported[i] = true;
    } else if (!m.merged) {
      if (const auto centre = reconstruct_centre(state_.tracks[i], predicted[i], features, options_.min_reconstruction_features)) {
        kalman[i] = update_with_position(kalman[i], *centre, options_.reconstruction_sigma_px);
        supported[i] = true;
      }
    }
  }
  // Two tracks on the halves of one long vehicle become one (paper IV-C).
  std::vector<bool> absorbed = merge_track_pieces(state_.tracks, kalman, region_hit, features, options_, scene_);
  for (size_t i = 0; i < n; ++i) absorbed[i] = absorbed[i] || resolved.absorbed[i];
  std::vector<OrientedBox> posterior(n);
  for (size_t i = 0; i < n; ++i) {
    posterior[i] = box_of(kalman[i].mean);
    store(kalman[i], state_.tracks[i]);
    // The anchor is the last measured box (region or features), where a stopping vehicle stands.
    if (region_hit[i] || supported[i]) state_.tracks[i].anchor_box = posterior[i];
    if (region_hit[i]) {
      refresh_feature_links(state_.tracks[i], posterior[i], features, options_.feature_uv_smoothing);
    }
  }

  // 6. Link new features (not during a merge, where the box is only reconstructed).
  // A vehicle's blob may be a part of it; its other features lie within a vehicle length.
  std::vector<OrientedBox> link_area = predicted;
  const double reach = vehicle_length_px * options_.link_min_length_factor;
  for (size_t i = 0; i < n; ++i) {
    const bool under_way = known[i] && cv::norm(velocities[i]) >= options_.heading_min_speed_px;
    if (under_way && link_area[i].length < reach) link_area[i].length = reach;
  }
  link_new_features(state_.tracks, link_area, posterior, velocities, known, may_link, features, options_);

  // 7. Lifecycle.
  std::vector<TrackRecord> live;
  std::vector<OrientedBox> live_boxes;
  for (size_t i = 0; i < n; ++i) {
    TrackRecord& t = state_.tracks[i];
    if (absorbed[i]) continue;  // a piece of another track's object
    record_frame(t, region_hit[i], supported[i], options_, wholly_inside_view(posterior[i], options_), confirm_min_speed_px);
    switch (decide_fate(t, inside_view(posterior[i], options_), options_)) {
      case Fate::Keep:
        live_boxes.push_back(posterior[i]);
        live.push_back(std::move(t));
        break;
      case Fate::Dormant:
        t.features.clear();
        t.frames_dormant = 0;
        state_.dormant.push_back(std::move(t));
        break;
      case Fate::Delete:
        break;
    }
  }
  state_.tracks = std::move(live);
  std::sort(state_.dormant.begin(), state_.dormant.end(), by_id);

  // 8. New tracks from free regions.
  initiate_tracks(resolved.free_regions, regions, live_boxes, features, options_, scene_, state_);
  std::sort(state_.tracks.begin(), state_.tracks.end(), by_id);

  for (const auto& t : state_.tracks) out.tracks.push_back(to_output(t));
  return out;
}

void Tracker::set_image_size(int width, int height) {
  options_.image_width = std::max(0, width);
  options_.image_height = std::max(0, height);
}

void Tracker::restore(const TrackerState& state) {
  auto check = [](const TrackRecord& t) {
    const KalmanState k = to_kalman(t);
    if (!is_finite(k) || t.id == 0) throw InvalidArgument("tracker state: track " + std::to_string(t.id) + " is not valid");
  };
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
