#pragma once
// Reads and decodes frames ahead on a thread of its own, into a short queue, so the publishing
// thread can keep a camera's schedule although one decode sometimes takes longer than a frame
// period (a 1080p JPEG takes about 10 ms here, much more when the host is busy).
//
//   FramePrefetcher ahead(open_frame_source(options), 3, [&](int64_t k) { return late_for(k); });
//   Frame frame;
//   while (ahead.next(frame)) publish(frame);
//
// `skip_undecoded(k)` is asked before frame k is read: true passes over it without decoding
// (live mode: it is already too late for it) and counts it in skipped().

#include <atomic>
#include <condition_variable>
#include <deque>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>

#include "uavmot/source/frame_source.hpp"

namespace uavmot::source {

class FramePrefetcher {
 public:
  FramePrefetcher(std::unique_ptr<FrameSource> source, size_t depth,
                  std::function<bool(int64_t index)> skip_undecoded = nullptr);
  // Stops the reading thread (frames still queued are dropped).
  ~FramePrefetcher();
  FramePrefetcher(const FramePrefetcher&) = delete;
  FramePrefetcher& operator=(const FramePrefetcher&) = delete;

  // The next frame in input order; false at the end. Rethrows the reader's InputError after the
  // frames read before it.
  bool next(Frame& frame);

  // Whether the following frame is decoded and waiting (a late frame is worth dropping only then).
  bool next_ready();
  const SourceInfo& info() const { return source_->info(); }
  int64_t skipped_undecoded() const { return skipped_.load(); }
  int64_t last_index() const { return last_index_.load(); }  // of the last frame read or skipped
  int64_t skipped_corrupt() const { return corrupt_.load(); }  // FrameSource::skipped() so far

 private:
  void run();

  std::unique_ptr<FrameSource> source_;
  size_t depth_;
  std::function<bool(int64_t)> skip_undecoded_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<Frame> queue_;
  bool done_ = false, stop_ = false;
  std::exception_ptr failure_;
  std::atomic<int64_t> skipped_{0}, corrupt_{0}, last_index_{0};
  std::thread thread_;
};

}  // namespace uavmot::source
