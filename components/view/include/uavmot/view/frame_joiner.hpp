#pragma once
// Joins one stream's frames with the chain's results for them by frame index, for drawing.
// The results arrive later than their frame (they pass through the chain) and in live mode some
// never arrive, so a frame is released when its tracks are there, or once it is `max_lag` frames
// older than the newest frame (drawn with whatever arrived). Frames come out in index order; the
// buffer never holds more than `max_lag` + a few entries.

#include <cstdint>
#include <map>
#include <optional>
#include <vector>

#include "uavmot/core/chain_types.hpp"

namespace uavmot::view {

struct JoinedFrame {
  Frame frame;
  std::optional<MotionEstimate> motion;
  std::optional<SegmentationResult> segmentation;
  std::optional<TrackList> tracks;
};

class FrameJoiner {
 public:
  explicit FrameJoiner(int max_lag = 10);

  void add_frame(Frame frame);
  void add_motion(MotionEstimate motion);
  void add_segmentation(SegmentationResult segmentation);
  void add_tracks(TrackList tracks);

  // Frames ready to draw, oldest first.
  std::vector<JoinedFrame> pop_ready();
  // Everything with a frame, oldest first (end of stream).
  std::vector<JoinedFrame> flush();

  size_t pending() const { return pending_.size(); }
  uint64_t released_incomplete() const { return incomplete_; }  // released before their tracks came
  uint64_t discarded() const { return discarded_; }              // results without a frame, late results

 private:
  struct Entry {
    std::optional<Frame> frame;
    std::optional<MotionEstimate> motion;
    std::optional<SegmentationResult> segmentation;
    std::optional<TrackList> tracks;
  };
  Entry* entry_for(int64_t index);  // null for an index already released
  JoinedFrame release(Entry& entry);

  int max_lag_;
  std::map<int64_t, Entry> pending_;
  int64_t newest_frame_ = 0;
  int64_t last_released_ = 0;
  uint64_t incomplete_ = 0;
  uint64_t discarded_ = 0;
};

}  // namespace uavmot::view
