#include "uavmot/view/frame_joiner.hpp"

#include <algorithm>

#include "uavmot/core/error.hpp"

namespace uavmot::view {

FrameJoiner::FrameJoiner(int max_lag) : max_lag_(max_lag) {
  if (max_lag < 0) throw InvalidArgument("FrameJoiner: max_lag must be >= 0");
}

FrameJoiner::Entry* FrameJoiner::entry_for(int64_t index) {
  if (index <= last_released_) {
    ++discarded_;
    return nullptr;
  }
  return &pending_[index];
}

void FrameJoiner::add_frame(Frame frame) {
  const int64_t index = frame.index;
  if (Entry* e = entry_for(index)) {
    e->frame = std::move(frame);
    newest_frame_ = std::max(newest_frame_, index);
  }
}
void FrameJoiner::add_motion(MotionEstimate motion) {
  if (Entry* e = entry_for(motion.frame_index)) e->motion = std::move(motion);
}
void FrameJoiner::add_segmentation(SegmentationResult segmentation) {
  if (Entry* e = entry_for(segmentation.frame_index)) e->segmentation = std::move(segmentation);
}
void FrameJoiner::add_tracks(TrackList tracks) {
  if (Entry* e = entry_for(tracks.frame_index)) e->tracks = std::move(tracks);
}

JoinedFrame FrameJoiner::release(Entry& entry) {
  if (!entry.tracks) ++incomplete_;
  return JoinedFrame{std::move(*entry.frame), std::move(entry.motion), std::move(entry.segmentation), std::move(entry.tracks)};
}

std::vector<JoinedFrame> FrameJoiner::pop_ready() {
  std::vector<JoinedFrame> out;
  while (!pending_.empty()) {
    auto it = pending_.begin();
    const int64_t index = it->first;
    Entry& e = it->second;
    // Also bounded when frames stop coming but results do.
    const bool stale = newest_frame_ - index >= max_lag_ || pending_.size() > 2 * static_cast<size_t>(max_lag_) + 8;
    if (!e.frame) {
      // Results whose frame never came (dropped in live mode): wait for it only as long as for tracks.
      if (!stale) break;
      ++discarded_;
    } else if (e.tracks || stale) {
      out.push_back(release(e));
    } else {
      break;  // keep order: the oldest frame waits for its tracks
    }
    last_released_ = index;
    pending_.erase(it);
  }
  return out;
}

std::vector<JoinedFrame> FrameJoiner::flush() {
  std::vector<JoinedFrame> out;
  for (auto& [index, e] : pending_) {
    if (e.frame) out.push_back(release(e));
    else ++discarded_;
    last_released_ = index;
  }
  pending_.clear();
  return out;
}

}  // namespace uavmot::view
