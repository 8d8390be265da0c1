#pragma once
// Split and merge handling (paper IV-C): turns the gating graph into at most one measurement per track.
//  - one region for one track: the region is the measurement;
//  - one region for several tracks (merge, e.g. overtaking): each track's centre is reconstructed from
//    its own linked features (median), its size is kept from the prediction;
//  - several regions for one track (split): regions that move alike and together fit the object are
//    fragments of it and are merged into one box, no larger than `largest_object_px` (width across,
//    height along; zero = no limit); otherwise the track keeps the region its features follow and
//    the others are free to start new tracks.
// A tentative track's claim on a region that an established track also validates is dropped first.
// A shared region no larger than one object (`max_object_size_px`: width across, height along) whose
// tracks move alike is one object tracked in pieces: the senior track (most hits) keeps it and the
// others are absorbed (deleted). Zero size disables this.

#include <vector>

#include "uavmot/tracking/feature_associator.hpp"
#include "uavmot/tracking/region_associator.hpp"

namespace uavmot::tracking {

enum class MeasurementKind { None, Box, Centre };

struct TrackMeasurement {
  MeasurementKind kind = MeasurementKind::None;
  OrientedBox box;       // kind == Box
  cv::Point2d centre;    // kind == Centre
  bool merged = false;   // in a merge this frame: its features must not be relearnt from this box
  bool size_jump = false;  // split off other regions or absorbed pieces: its size may change abruptly
};

struct SplitMergeResult {
  std::vector<TrackMeasurement> measurements;  // one per track
  std::vector<int> free_regions;               // ascending: may start new tracks
  std::vector<bool> absorbed;                  // per track: a piece of a senior track's object, to delete
};

// Median velocity of the moving features inside `box`; false when it holds none.
bool region_motion(const OrientedBox& box, const FeatureIndex& features, cv::Vec2d& velocity);

// The smallest oriented box around all of `boxes`.
OrientedBox enclosing_box(const std::vector<OrientedBox>& boxes);

SplitMergeResult resolve_split_merge(const RegionAssociation& gating, const std::vector<OrientedBox>& regions,
                                     const std::vector<TrackRecord>& tracks, const std::vector<OrientedBox>& predicted,
                                     const std::vector<cv::Vec2d>& velocities, const cv::Size2d& max_object_size_px,
                                     const FeatureIndex& features, const TrackerOptions& options,
                                     const cv::Size2d& largest_object_px = {});

}  // namespace uavmot::tracking
