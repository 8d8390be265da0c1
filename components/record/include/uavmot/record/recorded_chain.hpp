#pragma once
// The chain's results read back from a recording, as the chain's own types:
// - read_recorded_samples: motion estimates, segmentation results and track lists as recorded
//   (for scoring a recorded run: `uavmot eval --recording REC.mcap`);
// - read_recorded_chain: motion estimates and segmentation results paired by frame index, per
//   stream, in frame order (for re-running tracking on the ground: `uavmot process REC.mcap`).

#include <cstdint>
#include <functional>
#include <string>

#include "uavmot/core/chain_types.hpp"

namespace uavmot::record {

// What to do with each recorded sample of a topic; a topic without a handler is not read.
struct RecordedSampleHandlers {
  std::function<void(const MotionEstimate&)> motion;              // uavmot/motion
  std::function<void(const SegmentationResult&)> segmentation;    // uavmot/segmentation
  std::function<void(const TrackList&)> tracks;                   // uavmot/tracks
};

struct RecordedSampleCounts {
  uint64_t motion = 0, segmentation = 0, tracks = 0;  // samples handed on (end-of-stream markers not counted)
  uint64_t invalid = 0;                               // samples the chain's validation rejects (logged, skipped)
  std::string damage;                                 // the recording's damage (naming the offset), empty when intact
};

// Reads the topics that have a handler, in log-time order (per topic: the order they were
// published). Stops at damage (everything before it is delivered) and reports it. Throws
// InputError when the file is not MCAP or lacks a topic that has a handler.
RecordedSampleCounts read_recorded_samples(const std::string& path, const RecordedSampleHandlers& handlers);

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
