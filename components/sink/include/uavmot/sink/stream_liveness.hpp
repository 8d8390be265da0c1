#pragma once
// When a UAV vanishes (link lost, power lost, crashed) its stream stops without an end of stream.
// The ground must not wait for it forever: a bound stream that sent nothing for the timeout is
// declared lost, and the run counts it as done so the other streams' ends end the run. A lost
// stream that speaks again is back (its files were never closed, so nothing it sends is lost).

#include <chrono>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace uavmot::sink {

class StreamLiveness {
 public:
  using Clock = std::chrono::steady_clock;
  // TIMEOUT_S <= 0: streams are never declared lost.
  explicit StreamLiveness(double timeout_s) : timeout_(timeout_s) {}

  // A sample of STREAM (frame FRAME_INDEX) arrived at NOW. True when the stream was lost and is back.
  bool heard(const std::string& stream, int64_t frame_index, Clock::time_point now);
  // STREAM ended properly: never declared lost afterwards.
  void ended(const std::string& stream) { streams_[stream].ended = true; }
  // The streams that became lost at NOW (each reported once per loss).
  std::vector<std::string> newly_lost(Clock::time_point now);

  bool is_lost(const std::string& stream) const;
  size_t lost_count() const;
  // The last frame heard of STREAM (0 before any).
  int64_t last_frame(const std::string& stream) const;
  double timeout_s() const { return timeout_.count(); }

 private:
  struct State {
    Clock::time_point last_heard;
    int64_t last_frame = 0;
    bool ended = false, lost = false;
  };
  std::chrono::duration<double> timeout_;
  std::map<std::string, State> streams_;
};

}  // namespace uavmot::sink
