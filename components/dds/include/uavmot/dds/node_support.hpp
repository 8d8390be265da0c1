#pragma once
// Small pieces every chain node uses: publishing by delivery mode, a frame's output with its health
// report, end-of-stream samples and bookkeeping, latency from capture time, and once-per-cause
// logging of rejected samples.

#include <chrono>
#include <functional>
#include <map>
#include <set>
#include <stdexcept>
#include <string>

#include <spdlog/spdlog.h>

#include "uavmot/core/app.hpp"
#include "uavmot/dds/health_reporter.hpp"
#include "uavmot/dds/topic_writer.hpp"
#include "uavmot/dds/topics.hpp"
#include "uavmot/dds/upstream_watch.hpp"

namespace uavmot::dds {

inline int64_t wall_clock_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::system_clock::now().time_since_epoch()).count();
}

// Capture times on the wire are wall-clock (the source stamps them), so latency is now - capture.
inline double latency_ms_since(int64_t capture_time_ns) {
  return static_cast<double>(wall_clock_ns() - capture_time_ns) / 1e6;
}

// Lossless: wait for the readers (backpressure, nothing lost) up to `patience`. Live: never block the chain.
template <class PubSubType>
bool publish(TopicWriter<PubSubType>& writer, typename PubSubType::type& sample, DeliveryMode mode,
             std::chrono::milliseconds patience = kReaderPatience) {
  return mode == DeliveryMode::Lossless ? writer.write_reliably(sample, patience) : writer.write(sample);
}

// A lossless frame output its readers did not take within the writer's patience. Giving it up would
// lose it for good (the run could still end "complete"), so the process exits 1 instead; the
// launcher respawns it and the new one redoes the frame from its saved state and the writers'
// history, as after a crash (docs/launch.md, "Faults, component by component").
class OutputNotDelivered : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Called once a frame's output is published (e.g. to save state that includes that frame).
using PublishedHook = std::function<void(const std::string& stream, int64_t index)>;

// The output of frame INDEX, processed in PROCESS_MS: published by delivery mode (a sample live mode
// could not deliver counts as a drop; lossless mode throws OutputNotDelivered, or returns at once
// when the process is stopping), then PUBLISHED, then the frame's health report (its latency from
// CAPTURE_TIME_NS to now).
template <class PubSubType>
void publish_frame_output(TopicWriter<PubSubType>& writer, typename PubSubType::type& out, DeliveryMode mode,
                          HealthReporter& health, const PublishedHook& published, const std::string& stream, int64_t index,
                          double process_ms, int64_t capture_time_ns, std::chrono::milliseconds patience = kReaderPatience) {
  if (!publish(writer, out, mode, patience)) {
    if (mode == DeliveryMode::Lossless) {
      // Stopping (SIGTERM) during the wait: the frame was not sent, so it must not count as
      // published; its state is not saved and a resumed run redoes it.
      if (shutdown_requested()) return;
      throw OutputNotDelivered(writer.topic() + ": the output of frame " + std::to_string(index) + " of stream '" + stream +
                               "' was not taken by its readers within " + std::to_string(patience.count()) +
                               " ms; exiting, so that a restarted process redoes it (giving it up would lose it)");
    }
    health.dropped();
  }
  if (published) published(stream, index);
  health.frame_out(index, process_ms, latency_ms_since(capture_time_ns));
  health.set_bytes_out(writer.bytes_sent());
}

// A component whose inputs have had no writer for the upstream timeout: says why, reports FAILED,
// and returns the exit code (dds/upstream_watch.hpp).
inline int give_up_on_upstream(const UpstreamWatch& upstream, HealthReporter& health, const std::string& inputs) {
  spdlog::error("{}", upstream.message(inputs));
  health.report(msg::ComponentState::FAILED);
  return kExitFailure;
}

// How long an end of stream (and the flush after it) may wait for the readers: in lossless mode as
// long as any sample (a stalled link or a slow reader must not cost the end of stream), in live
// mode briefly.
inline std::chrono::seconds end_of_stream_patience(DeliveryMode mode) {
  return mode == DeliveryMode::Lossless ? std::chrono::seconds(60) : std::chrono::seconds(10);
}

// Passes the end of STREAM on (its last frame INDEX), waiting for the readers as end_of_stream_patience says.
template <class PubSubType>
void write_end_of_stream(TopicWriter<PubSubType>& writer, const std::string& stream, int64_t index, DeliveryMode mode) {
  typename PubSubType::type eos;
  eos.stream_id(stream);
  eos.frame_index(index);
  eos.end_of_stream(true);
  writer.write_reliably(eos, end_of_stream_patience(mode));
}

// Which streams have ended; a node exits when the expected number has.
class StreamEnds {
 public:
  explicit StreamEnds(int expected) : expected_(expected) {}
  void end(const std::string& stream) { ended_.insert(stream); }
  bool ended(const std::string& stream) const { return ended_.count(stream) > 0; }
  bool all_ended() const { return static_cast<int>(ended_.size()) >= expected_; }

 private:
  int expected_;
  std::set<std::string> ended_;
};

// Logs a rejected sample once per cause (then every 100th), so garbage on the wire cannot flood the log.
class RejectLog {
 public:
  void log(const std::string& topic, const std::string& why) {
    const uint64_t n = ++counts_[topic + ": " + why.substr(0, why.find_first_of("0123456789"))];
    if (n == 1 || n % 100 == 0) spdlog::warn("{}: dropped a malformed sample ({}x): {}", topic, n, why);
  }

 private:
  std::map<std::string, uint64_t> counts_;
};

}  // namespace uavmot::dds
