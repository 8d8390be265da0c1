#pragma once
// Chain types <-> the per-frame downlink sample (idl/downlink.idl): what crosses the air -> ground
// link. Only what the ground uses travels: the homography (exact), regions and tracks as float32
// boxes and velocities (1e-4 px at 1000 px, below the 1/1000 px the result files print), no
// features, clusters, uncertainties or feature ids. Received samples are validated like the
// full ones.

#include <optional>
#include <string>

#include "downlink.h"
#include "uavmot/core/chain_types.hpp"

namespace uavmot::dds {

// One frame's results as the UAV's chain produced them; a part it skipped is absent.
struct FrameParts {
  std::optional<MotionEstimate> motion;
  std::optional<SegmentationResult> segmentation;
  std::optional<TrackList> tracks;
};

// Tracks whose id does not fit the compact id (32 bits) are left out and counted in `dropped_tracks`.
msg::FrameResults to_downlink_msg(const std::string& stream_id, int64_t frame_index, const FrameParts& parts,
                                  uint64_t* dropped_tracks = nullptr);

// What the ground gets back: features, clusters, uncertainties and feature ids are empty/zero.
// nullopt with `why` set when the sample is malformed.
std::optional<FrameParts> from_msg(const msg::FrameResults& sample, std::string& why);

}  // namespace uavmot::dds
