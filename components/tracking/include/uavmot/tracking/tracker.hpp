#pragma once
// Multi-object tracking (paper section IV): regions from segmentation are the Kalman filter's
// measurements, moving local features support split and merge handling, and the frame-to-frame
// homography is the filter's control input.
//
//   uavmot::tracking::Tracker tracker(options, scene);
//   for (...) { TrackList tracks = tracker.process(motion_estimate, segmentation_result); }

#include <memory>

#include "uavmot/core/chain_types.hpp"
#include "uavmot/core/scene_info.hpp"
#include "uavmot/tracking/tracker_options.hpp"
#include "uavmot/tracking/tracker_state.hpp"

namespace uavmot::tracking {

struct TrackerStages;  // the steps of one frame behind small interfaces (src/stages.hpp)

class Tracker {
 public:
  // Throws uavmot::InvalidArgument for options outside their ranges.
  explicit Tracker(TrackerOptions options = {}, SceneInfo scene = {});

  // One frame: predict with the homography, assign regions and features, handle split and merge,
  // update, start, confirm and delete tracks. Non-finite homographies, regions and features are
  // ignored (counted in state()). Returns tentative, confirmed and coasting tracks, ascending id.
  // The image size comes with the motion estimate (image_width/height; TrackerOptions' as the
  // fallback when it carries none): a track whose centre leaves the image is hidden at once.
  TrackList process(const MotionEstimate& motion, const SegmentationResult& segmentation);

  TrackerState state() const { return state_; }
  // Throws uavmot::InvalidArgument for a state that is not self-consistent (e.g. non-finite values).
  void restore(const TrackerState& state);

  const TrackerOptions& options() const { return options_; }

 private:
  TrackerOptions options_;
  SceneInfo scene_;
  std::shared_ptr<const TrackerStages> stages_;  // stateless, chosen from options_ (src/stages.hpp)
  TrackerState state_;
};

// A track's ground speed with the scene's GSD and frame rate.
double speed_mps(const Track& track, const SceneInfo& scene);
double speed_kmh(const Track& track, const SceneInfo& scene);

}  // namespace uavmot::tracking
