#pragma once
// Assignment of local features to tracks (paper IV-B). A moving feature is linked to a track when
// (1) it is not linked to any track, (2) it lies inside the track's Kalman prediction, (3) it lies
// inside no other track's prediction, and (4) its motion is similar in magnitude and direction to
// the track's. A track keeps at most `max_features_per_track` links; each stores where the feature
// sits on the box (to_box_coordinates) so the box centre can be reconstructed from the feature
// alone when regions merge. Links to vanished features and outliers in position or motion are removed.

#include <optional>
#include <vector>

#include "uavmot/core/chain_types.hpp"
#include "uavmot/core/spatial_grid.hpp"
#include "track_in_frame.hpp"
#include "uavmot/tracking/tracker_options.hpp"
#include "uavmot/tracking/tracker_state.hpp"

namespace uavmot::tracking {

// This frame's valid moving features, by id and by position; and the features that stopped moving but
// are still tracked. A stopped feature only keeps supporting a link made while it moved, and only an
// established one: a vehicle that slows to a halt keeps its track, a brief false motion does not.
class FeatureIndex {
 public:
  // Any order; stored ascending id. `stopped_link_min_frames` = 0: stopped features support nothing.
  explicit FeatureIndex(std::vector<TrackedFeature> moving, std::vector<TrackedFeature> stopped = {},
                        uint32_t stopped_link_min_frames = 0);

  const std::vector<TrackedFeature>& all() const { return features_; }  // the moving ones
  const TrackedFeature* find(uint64_t id) const;                        // a moving one
  // The feature behind a link: moving, or stopped when the link is at least stopped_link_min_frames old.
  const TrackedFeature* find_linked(const FeatureLink& link) const;
  // Indices into all() of the moving features inside `box`, ascending.
  std::vector<int> inside(const OrientedBox& box) const;

 private:
  std::vector<TrackedFeature> features_;
  std::vector<TrackedFeature> stopped_;
  uint32_t stopped_link_min_frames_ = 0;
  SpatialGrid grid_;
};

cv::Vec2d median_velocity(const std::vector<cv::Vec2d>& velocities);

// Criterion (4): |v - reference| within the absolute or relative tolerance, and for a clearly moving
// reference, a direction within the angular tolerance.
bool similar_motion(const cv::Vec2d& v, const cv::Vec2d& reference, const TrackerOptions& options);

// Where `link`'s feature at `position` puts the centre of a box shaped like `box`.
cv::Point2d centre_from_feature(const OrientedBox& box, const FeatureLink& link, const cv::Point2d& position);

// Removes links whose feature vanished or stopped moving, left the predicted box (beyond the margin),
// moves unlike the others, or reconstructs a centre far from the median.
void prune_feature_links(TrackRecord& track, const OrientedBox& predicted, const cv::Vec2d& track_velocity,
                         bool velocity_known, const FeatureIndex& features, const TrackerOptions& options);

// Median of the centres reconstructed by the track's linked features; nullopt with too few links.
std::optional<cv::Point2d> reconstruct_centre(const TrackRecord& track, const OrientedBox& predicted,
                                              const FeatureIndex& features, int min_features);

// The features behind the track's links present this frame (moving, or stopped on an established
// link), in link order.
std::vector<const TrackedFeature*> linked_features(const TrackRecord& track, const FeatureIndex& features);

// Median velocity of `linked`; nullopt with fewer than min_features.
std::optional<cv::Vec2d> median_velocity_of(const std::vector<const TrackedFeature*>& linked, int min_features);

// Median velocity of the track's linked features present this frame; nullopt with fewer than min_features.
std::optional<cv::Vec2d> linked_velocity(const TrackRecord& track, const FeatureIndex& features, int min_features);

// Links new features to the tracks updated with a region (region_hit) by the four criteria. Criteria
// 2 and 3 look in the predictions, lengthened for a track under way (velocity known, at least
// heading_min_speed_px) to `min_search_length_px` at least: a vehicle's blob may be a part of it, its
// other features lie within a vehicle length. A link stores where the feature sits on the posterior
// box. The velocity compared with is the track's when known, else the candidates' median motion.
void link_new_features(std::vector<TrackInFrame>& tracks, const FeatureIndex& features, const TrackerOptions& options,
                       double min_search_length_px);

// After an unambiguous region update, lets the stored box positions follow the new box slowly.
void refresh_feature_links(TrackRecord& track, const OrientedBox& posterior, const FeatureIndex& features,
                           double smoothing);

}  // namespace uavmot::tracking
