#pragma once
// Chain types <-> the per-frame downlink sample (idl/downlink.idl): what crosses the air -> ground
// link. Only what the ground uses travels, exactly, so the ground's files are byte-identical to
// `uavmot process`'s: the homography as float64, tracks' boxes and velocities as float32 (the
// tracker rounds them to float32: core round_to_float32), regions as the numbers regions.txt
// prints (core PrintedRegion); no features, clusters, uncertainties or feature ids. Received samples are validated like the full ones.

#include <optional>
#include <string>

#include "downlink.h"
#include "uavmot/core/chain_types.hpp"
#include "uavmot/core/result_files.hpp"

namespace uavmot::dds {

// One frame's results as the UAV's chain produced them; a part it skipped is absent.
struct FrameParts {
  std::optional<MotionEstimate> motion;
  std::optional<SegmentationResult> segmentation;
  std::optional<TrackList> tracks;
};

// What the ground gets of a frame: regions as printed, motion without features, tracks without
// uncertainties and feature ids.
struct GroundFrame {
  std::optional<MotionEstimate> motion;
  std::optional<std::vector<PrintedRegion>> regions;
  std::optional<TrackList> tracks;
};

// Left out and counted: tracks whose id does not fit 32 bits, regions whose printed numbers do not
// fit the compact fields (never for valid samples: see the limits in downlink_convert.cpp).
// Counted only: tracks sent rounded because they were not float32 values (not from uavmot's
// tracker); the ground's files may then differ from the air's in a last digit.
struct DownlinkDrops {
  uint64_t tracks = 0;
  uint64_t regions = 0;
  uint64_t inexact_tracks = 0;
};
msg::FrameResults to_downlink_msg(const std::string& stream_id, int64_t frame_index, const FrameParts& parts,
                                  DownlinkDrops* drops = nullptr);

// nullopt with `why` set when the sample is malformed.
std::optional<GroundFrame> from_msg(const msg::FrameResults& sample, std::string& why);

}  // namespace uavmot::dds
