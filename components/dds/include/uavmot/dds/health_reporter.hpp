#pragma once
// Publishes a component's ComponentHealth on uavmot/health about once a second:
// rate, processing time, latency, queue depth, drops and rejected samples.

#include <chrono>
#include <functional>
#include <memory>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "healthPubSubTypes.h"
#include "uavmot/dds/participant.hpp"

namespace uavmot::dds {

class HealthReporter {
 public:
  HealthReporter(Participant& participant, std::string component, std::string stream_id,
                 std::chrono::milliseconds period = std::chrono::seconds(1));

  void frame_in() { ++frames_in_; }
  // One frame done: how long it took and how old its data was when published. Reports when due (tick).
  void frame_out(int64_t frame_index, double processing_ms, double latency_ms = 0.0);
  void dropped(uint64_t count = 1) { dropped_ += count; }
  void invalid_sample() { ++invalid_; }
  void set_queue_depth(uint32_t depth) { queue_depth_ = depth; }
  void set_bytes_out(uint64_t bytes) { bytes_out_ = bytes; }

  // Reports what this writer wrote / this reader took, per topic, on every health report
  // (`uavmot status` turns successive counts into bytes/s). The endpoint must outlive the reporter.
  // A writer this component publishes with also ticks the reports while it waits for its readers
  // (lossless backpressure): reports stop only when the component itself stops. Only on the thread
  // that made the reporter, the one that reports.
  template <class PubSubType>
  void watch(TopicWriter<PubSubType>& writer) {
    writer.set_while_waiting([this, owner = std::this_thread::get_id()] {
      if (std::this_thread::get_id() == owner) tick();
    });
    watch(static_cast<const TopicWriter<PubSubType>&>(writer));
  }
  template <class PubSubType>
  void watch(const TopicWriter<PubSubType>& writer) {
    watched_.emplace_back(writer.topic(), [&writer](msg::TopicTraffic& t) {
      t.samples_out(t.samples_out() + writer.samples_sent());
      t.bytes_out(t.bytes_out() + writer.bytes_sent());
    });
  }
  template <class PubSubType>
  void watch(const TopicReader<PubSubType>& reader) {
    watched_.emplace_back(reader.topic(), [&reader](msg::TopicTraffic& t) {
      t.samples_in(t.samples_in() + reader.samples_taken());
      t.bytes_in(t.bytes_in() + reader.bytes_taken());
    });
  }

  // Publishes when the period has passed since the last report.
  void tick();
  // Publishes now with the given state (e.g. FINISHED or FAILED at the end) and message.
  void report(msg::ComponentState state, const std::string& message = "");

  uint64_t invalid_samples() const { return invalid_; }
  uint64_t dropped_count() const { return dropped_; }

 private:
  std::unique_ptr<TopicWriter<msg::ComponentHealthPubSubType>> writer_;
  std::string component_;
  std::string stream_id_;
  std::chrono::milliseconds period_;
  std::chrono::steady_clock::time_point last_report_;
  msg::ComponentState state_ = msg::ComponentState::STARTING;
  uint64_t frames_in_ = 0, frames_out_ = 0, dropped_ = 0, invalid_ = 0, bytes_out_ = 0;
  uint32_t queue_depth_ = 0;
  std::vector<std::pair<std::string, std::function<void(msg::TopicTraffic&)>>> watched_;
  int64_t last_frame_ = 0;
  // Sums since the last report, for means.
  uint64_t window_frames_ = 0;
  double window_processing_ms_ = 0.0, window_latency_ms_ = 0.0;
};

}  // namespace uavmot::dds
