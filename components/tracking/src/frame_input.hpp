#pragma once
// One frame's input to the tracker, validated (step 1 of Tracker::process): a usable homography,
// the regions that are measurements, the valid features, and the image size.

#include <vector>

#include <opencv2/core/types.hpp>

#include "feature_associator.hpp"
#include "uavmot/core/chain_types.hpp"
#include "uavmot/tracking/tracker_options.hpp"
#include "uavmot/tracking/tracker_state.hpp"

namespace uavmot::tracking {

struct FrameInput {
  Homography homography;            // frame k-1 -> k; the identity when the estimate's was broken
  std::vector<OrientedBox> regions;  // of the selected method, finite, length the longer side
  FeatureIndex features;            // moving ones, and stopped ones that a track links to
  cv::Size image;                   // the motion estimate's image size; 0 x 0: unknown
};

// Reads and validates one frame. Counts what it rejects in `state` (rejected_*); the stopped
// features kept are those that the tracks of state.tracks which have travelled
// stopped_link_min_travel_lengths vehicle lengths (of `scene`) link to.
FrameInput read_frame_input(const MotionEstimate& motion, const SegmentationResult& segmentation,
                            const TrackerOptions& options, const SceneInfo& scene, TrackerState& state);

}  // namespace uavmot::tracking
