#pragma once
// A one-line progress display for long runs: frame, rate and ETA, redrawn in place on a
// terminal, a plain line every few seconds otherwise (logs stay readable).

#include <chrono>
#include <cstdint>
#include <string>

namespace uavmot::pipeline {

class Progress {
 public:
  Progress(std::string label, int64_t total_frames, bool enabled = true);
  void update(int64_t frames_done);
  void finish();

 private:
  std::string label_;
  int64_t total_;
  bool enabled_;
  bool terminal_;
  int64_t done_ = 0;
  std::chrono::steady_clock::time_point start_, last_print_;
};

}  // namespace uavmot::pipeline
