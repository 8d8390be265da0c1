#pragma once
// Split and merge handling (paper IV-C): turns the gating graph into at most one measurement per track.
//  - one region for one track: the region is the measurement;
//  - one region for several tracks (merge, e.g. overtaking): each track's centre is reconstructed from
//    its own linked features (median), its size is kept from the prediction;
//  - a track's own region wider than any vehicle (`widest_region`) holds it and an untracked
//    neighbour: the track takes the part in its own lane (`within_lane_of`);
//  - several regions for one track (split): regions that move alike and together fit the object are
//    fragments of it and are merged into one box, no larger than `largest_object_px` (width across,
//    height along; zero = no limit); otherwise the track keeps the region its features follow and
//    the others are free to start new tracks.
// A tentative track's claim on a region that an established track also validates is dropped first.
// A shared region no larger than one object whose tracks move alike is one object tracked in pieces:
// the senior track (most hits) keeps it and the others are absorbed (deleted).

#include <vector>

#include "feature_associator.hpp"
#include "region_associator.hpp"
#include "track_in_frame.hpp"
#include "uavmot/core/scene_info.hpp"

namespace uavmot::tracking {

// Object sizes in px, width across and height along (zero = no limit).
struct ObjectLimits {
  cv::Size2d single_object;  // a shared region within this holds one object tracked in pieces
  cv::Size2d largest_object;  // no box assembled from fragments (or pieces of a vehicle) is larger
  double widest_region = 0.0;  // a region wider than this along a track's axis holds more than one object (zero = no limit)
};

// single_object_size_factor x the scene's vehicle; max_object_width_m x max_object_length_factor
// vehicle lengths; max_region_width_m.
ObjectLimits object_limits(const TrackerOptions& options, const SceneInfo& scene);

struct SplitMergeResult {
  std::vector<TrackMeasurement> measurements;  // one per track
  std::vector<int> free_regions;               // ascending: may start new tracks
  std::vector<bool> absorbed;                  // per track: a piece of a senior track's object, to delete
};

// Median velocity of the moving features inside `box`; false when it holds none.
bool region_motion(const OrientedBox& box, const FeatureIndex& features, cv::Vec2d& velocity);

// The part of `region` in the lane of `predicted`: `region` read along the predicted axis, cut across
// to the predicted box's width (where they overlap; the predicted span where they do not).
OrientedBox within_lane_of(const OrientedBox& region, const OrientedBox& predicted);

// The smallest oriented box around all of `boxes`.
OrientedBox enclosing_box(const std::vector<OrientedBox>& boxes);

// Reads each track's record, predicted box and velocity.
SplitMergeResult resolve_split_merge(const RegionAssociation& gating, const std::vector<OrientedBox>& regions,
                                     const std::vector<TrackInFrame>& tracks, const FeatureIndex& features,
                                     const TrackerOptions& options, const ObjectLimits& limits);

}  // namespace uavmot::tracking
