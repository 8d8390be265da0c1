#pragma once
// The chain's intermediate results read back from a recording: motion estimates and
// segmentation results paired by frame index, per stream, in frame order. For re-running
// tracking on the ground with new parameters (`uavmot process REC.mcap`).

#include <cstdint>
#include <functional>
#include <string>

#include "uavmot/core/chain_types.hpp"

namespace uavmot::record {

struct RecordedChainCounts {
  uint64_t pairs = 0;             // frames with both a motion estimate and a segmentation result
  uint64_t unpaired = 0;          // frames where one of the two is missing from the recording
  uint64_t invalid = 0;           // samples the chain's validation rejects
  std::string damage;             // the recording's damage (naming the offset), empty when intact
};

using RecordedPairHandler =
    std::function<void(const std::string& stream, const MotionEstimate& motion, const SegmentationResult& segmentation)>;

// Reads uavmot/motion and uavmot/segmentation from the MCAP file and calls `handle` for each
// frame that has both, per stream in frame order. Stops at damage (everything before it is
// delivered) and reports it. Throws InputError when the file is not MCAP or holds neither topic.
RecordedChainCounts read_recorded_chain(const std::string& path, const RecordedPairHandler& handle);

}  // namespace uavmot::record
