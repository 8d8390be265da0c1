#include "uavmot/sink/stream_liveness.hpp"

#include <algorithm>

namespace uavmot::sink {

bool StreamLiveness::heard(const std::string& stream, int64_t frame_index, Clock::time_point now) {
  State& s = streams_[stream];
  s.last_heard = now;
  s.last_frame = std::max(s.last_frame, frame_index);
  const bool back = s.lost;
  s.lost = false;
  return back;
}

std::vector<std::string> StreamLiveness::newly_lost(Clock::time_point now) {
  std::vector<std::string> lost;
  if (timeout_.count() <= 0) return lost;
  for (auto& [id, s] : streams_) {
    if (s.ended || s.lost || now - s.last_heard <= timeout_) continue;
    s.lost = true;
    lost.push_back(id);
  }
  return lost;
}

bool StreamLiveness::is_lost(const std::string& stream) const {
  const auto it = streams_.find(stream);
  return it != streams_.end() && it->second.lost;
}

size_t StreamLiveness::lost_count() const {
  return static_cast<size_t>(std::count_if(streams_.begin(), streams_.end(), [](const auto& e) { return e.second.lost; }));
}

int64_t StreamLiveness::last_frame(const std::string& stream) const {
  const auto it = streams_.find(stream);
  return it == streams_.end() ? 0 : it->second.last_frame;
}

}  // namespace uavmot::sink
