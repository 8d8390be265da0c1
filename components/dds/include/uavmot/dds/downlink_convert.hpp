#pragma once
// Chain types <-> the compact downlink samples (idl/downlink.idl): what crosses the air -> ground
// link. Only what the ground uses travels: the homography (exact), regions and tracks as float32
// boxes and velocities (1e-4 px at 1000 px, below the 1/1000 px the result files print), no
// features, clusters, uncertainties or feature ids. Received samples are validated like the
// full ones.

#include <optional>
#include <string>

#include "downlink.h"
#include "uavmot/core/chain_types.hpp"

namespace uavmot::dds {

msg::MotionSummary to_downlink_msg(const MotionEstimate& motion);
msg::RegionList to_downlink_msg(const SegmentationResult& segmentation);
msg::CompactTrackList to_downlink_msg(const TrackList& tracks);

// What the ground gets back: features, clusters, uncertainties and feature ids are empty/zero.
// nullopt with `why` set when the sample is malformed.
std::optional<MotionEstimate> from_msg(const msg::MotionSummary& sample, std::string& why);
std::optional<SegmentationResult> from_msg(const msg::RegionList& sample, std::string& why);
std::optional<TrackList> from_msg(const msg::CompactTrackList& sample, std::string& why);

}  // namespace uavmot::dds
