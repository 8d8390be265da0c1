#pragma once
// The steps of one frame (docs/tracking.md, "One frame"), each behind a small interface, in the
// manner of Stone Soup and Autoware's multi_object_tracker. Tracker::process calls them in order
// and knows no algorithm; make_stages() builds the set TrackerOptions asks for (today the motion
// model is chosen by name, every other stage has the paper's implementation only). Stages hold
// their options and keep no state between frames: all of it is in TrackerState.

#include <memory>
#include <vector>

#include "deleter.hpp"
#include "frame_input.hpp"
#include "motion_model.hpp"
#include "region_associator.hpp"
#include "track_in_frame.hpp"
#include "uavmot/core/scene_info.hpp"

namespace uavmot::tracking {

// Regions to tracks (paper IV-A): the gating graph between this frame's regions and the predictions.
class RegionAssociator {
 public:
  virtual ~RegionAssociator() = default;
  virtual RegionAssociation associate(const std::vector<OrientedBox>& regions,
                                      const std::vector<TrackInFrame>& tracks) const = 0;
};

// Local features to tracks (paper IV-B).
class FeatureAssociator {
 public:
  virtual ~FeatureAssociator() = default;
  // Before association: drops links whose feature vanished or became an outlier.
  virtual void prune(std::vector<TrackInFrame>& tracks, const FeatureIndex& features) const = 0;
  // After the update: links new features to the tracks updated with a region.
  virtual void link(std::vector<TrackInFrame>& tracks, const FeatureIndex& features) const = 0;
};

// Split and merge handling (paper IV-C).
class SplitMerge {
 public:
  virtual ~SplitMerge() = default;
  // One measurement per track from the gating graph (sets measurement, absorbed); returns the
  // regions free to start tracks, ascending.
  virtual std::vector<int> resolve(const RegionAssociation& gating, const FrameInput& input,
                                   std::vector<TrackInFrame>& tracks) const = 0;
  // After the update: tracks on the pieces of one long vehicle become one (sets absorbed).
  virtual void merge_pieces(std::vector<TrackInFrame>& tracks, const FeatureIndex& features) const = 0;
};

// The Kalman update of one track (paper IV-D).
class Updater {
 public:
  virtual ~Updater() = default;
  // Its linked features' motion, then its measurement (or features alone); sets region_hit, supported.
  virtual void update(TrackInFrame& track, const FeatureIndex& features) const = 0;
  // Writes the posterior into the record; a measured track's anchor and feature links follow it.
  virtual void commit(TrackInFrame& track, const FeatureIndex& features) const = 0;
};

// New tracks from free regions, and re-acquisition of dormant ones (paper IV-A).
class Initiator {
 public:
  virtual ~Initiator() = default;
  // Appends to state.tracks, whose current boxes are `live_boxes`.
  virtual void initiate(const std::vector<int>& free_regions, const FrameInput& input,
                        const std::vector<OrientedBox>& live_boxes, TrackerState& state) const = 0;
};

// Lifecycle (paper IV-D): confirmation, coasting, dormancy, deletion.
class Deleter {
 public:
  virtual ~Deleter() = default;
  // Carries dormant tracks through the homography and deletes the expired ones.
  virtual void age_dormant(TrackerState& state, const Homography& h) const = 0;
  // Records the frame in the track's history and decides what happens to it.
  virtual Fate judge(TrackInFrame& track, const FrameInput& in) const = 0;
};

struct TrackerStages {
  std::unique_ptr<MotionModel> motion_model;
  std::unique_ptr<FeatureAssociator> feature_associator;
  std::unique_ptr<RegionAssociator> region_associator;
  std::unique_ptr<SplitMerge> split_merge;
  std::unique_ptr<Updater> updater;
  std::unique_ptr<Initiator> initiator;
  std::unique_ptr<Deleter> deleter;
};

// The stages `options` select (validated options; scene with a positive GSD).
TrackerStages make_stages(const TrackerOptions& options, const SceneInfo& scene);

}  // namespace uavmot::tracking
