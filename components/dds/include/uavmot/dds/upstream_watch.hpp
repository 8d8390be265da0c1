#pragma once
// Tells a restarted component that its stream ended without it. A component respawned after its
// upstream had already written the end of stream and exited (e.g. a sink that failed just as the
// end arrived) would wait forever: no writer of its inputs will ever match again. Given a timeout,
// it gives up once none of its inputs has had a matched writer for that long.

#include <chrono>
#include <string>

#include <fmt/format.h>

namespace uavmot::dds {

class UpstreamWatch {
 public:
  using Clock = std::chrono::steady_clock;

  // timeout_s <= 0: never give up (the default: a component started first waits for its upstream).
  explicit UpstreamWatch(double timeout_s, Clock::time_point start = Clock::now())
      : timeout_(std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(timeout_s))),
        enabled_(timeout_s > 0),
        last_writer_seen_(start) {}

  // `writers_matched`: writers matched now, summed over the inputs. True once there has been none for
  // the timeout (counted from construction or from the last call that saw one).
  bool gone(int writers_matched, Clock::time_point now = Clock::now()) {
    if (!enabled_) return false;
    if (writers_matched > 0) {
      last_writer_seen_ = now;
      return false;
    }
    return now - last_writer_seen_ >= timeout_;
  }

  double timeout_s() const { return std::chrono::duration<double>(timeout_).count(); }

  // The error a component logs when it gives up (one wording for every component).
  std::string message(const std::string& inputs) const {
    return fmt::format("no writer of {} for {:g} s (--upstream-timeout): the stream ended before this process "
                       "(re)started and nothing more can arrive; giving up with what was written",
                       inputs, timeout_s());
  }

 private:
  Clock::duration timeout_;
  bool enabled_;
  Clock::time_point last_writer_seen_;
};

}  // namespace uavmot::dds
