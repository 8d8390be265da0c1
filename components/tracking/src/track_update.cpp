#include "track_update.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "updater.hpp"
#include "vector_angles.hpp"

namespace uavmot::tracking {
namespace {

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
  const double heading = direction_deg(*velocity);
  kalman = update_with_heading(kalman, heading, options.heading_sigma_deg);
  return heading;
}

// Without a feature heading, a track that has travelled far enough names its own: the direction of
// its recent travel (a vehicle drives along its length). A small or slow car often has one feature,
// or none fast enough, for a feature heading; its blob's own axis is then noise (docs/tracking.md,
// sessions 39 and 42).
std::optional<double> update_with_travel_heading(KalmanState& kalman, const TrackRecord& record,
                                                const TrackerOptions& options, double vehicle_length_px) {
  if (!(options.travel_heading_min_lengths > 0.0) || !(options.heading_sigma_deg > 0.0)) return std::nullopt;
  const cv::Vec2d travel(kalman.mean(kX) - record.travel_from.x, kalman.mean(kY) - record.travel_from.y);
  const double distance = cv::norm(travel);
  if (distance < options.travel_heading_min_lengths * vehicle_length_px) return std::nullopt;
  const double heading = direction_deg(travel);
  // After a bend the chord no longer points where the track goes: withheld while the track's own
  // velocity points more than travel_heading_max_turn_deg away, and trusted less the more they differ.
  const cv::Vec2d velocity(kalman.mean(kVx), kalman.mean(kVy));
  const double turn_deg = cv::norm(velocity) > 0.0 ? angle_between_deg(velocity, travel) : 0.0;
  if (options.travel_heading_max_turn_deg > 0.0 && turn_deg > options.travel_heading_max_turn_deg) return std::nullopt;
  // The ends of the travel are each known to about a region's position noise.
  const double sigma = std::max({options.heading_sigma_deg, turn_deg,
                                 std::atan2(2.0 * options.region_position_sigma_px, distance) * 180.0 / M_PI});
  kalman = update_with_heading(kalman, heading, sigma);
  return heading;
}

// Pulls the start of the track's recent travel after it, to at most `max_px` behind its centre.
void follow_travel(TrackRecord& record, const KalmanState& kalman, double max_px) {
  if (!(max_px > 0.0)) return;
  const cv::Point2d centre(kalman.mean(kX), kalman.mean(kY));
  const cv::Point2d behind = record.travel_from - centre;
  const double distance = std::hypot(behind.x, behind.y);
  if (distance > max_px) record.travel_from = centre + behind * (max_px / distance);
}

}  // namespace

void update_track(TrackInFrame& track, const FeatureIndex& features, const TrackerOptions& options,
                  double vehicle_length_px) {
  const TrackMeasurement& m = track.measurement;
  follow_travel(track.record, track.kalman, options.travel_heading_max_lengths * vehicle_length_px);
  const std::vector<const TrackedFeature*> linked = linked_features(track.record, features);
  std::optional<double> heading = update_with_feature_motion(track.kalman, linked, options);
  if (m.kind == MeasurementKind::Box) {
    if (!heading) heading = update_with_travel_heading(track.kalman, track.record, options, vehicle_length_px);
    OrientedBox box = heading ? box_along_heading(m.box, *heading) : m.box;
    if (heading && options.feature_span_margin_px >= 0.0) {
      std::vector<cv::Point2d> points;
      for (const TrackedFeature* f : linked) points.push_back(f->position);
      box = lengthen_to_cover(box, points, options.feature_span_margin_px, vehicle_length_px);
    }
    if (m.size_jump) open_size_uncertainty(track.kalman, box);
    track.kalman = update_with_box(track.kalman, box, box_measurement_noise(options), options.min_box_size_px);
    track.region_hit = true;
  } else if (m.kind == MeasurementKind::Centre) {
    track.kalman = update_with_position(track.kalman, m.centre, options.reconstruction_sigma_px);
    track.supported = true;
  } else if (!m.merged) {
    // Features alone keep a track alive.
    if (const auto centre =
            reconstruct_centre(track.record, track.predicted, features, options.min_reconstruction_features)) {
      track.kalman = update_with_position(track.kalman, *centre, options.reconstruction_sigma_px);
      track.supported = true;
    }
  }
}

void commit_update(TrackInFrame& track, const FeatureIndex& features, double uv_smoothing) {
  track.posterior = box_of(track.kalman.mean);
  store(track.kalman, track.record);
  // The anchor is the last measured box (region or features), where a stopping vehicle stands.
  if (track.region_hit || track.supported) track.record.anchor_box = track.posterior;
  if (track.region_hit) refresh_feature_links(track.record, track.posterior, features, uv_smoothing);
}

}  // namespace uavmot::tracking
