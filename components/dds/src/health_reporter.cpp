#include "uavmot/dds/health_reporter.hpp"

#include <unistd.h>

#include <map>

#include "uavmot/dds/health_partitions.hpp"

namespace uavmot::dds {

HealthReporter::HealthReporter(Participant& participant, std::string component, std::string stream_id,
                               std::chrono::milliseconds period)
    // In its own partition: the one its certificate may report in (health_partitions.hpp).
    : writer_(participant.make_writer_in<msg::ComponentHealthPubSubType>(health_partition(component), kHealthTopic,
                                                                        TopicClass::Health)),
      component_(std::move(component)),
      stream_id_(std::move(stream_id)),
      period_(period),
      last_report_(std::chrono::steady_clock::now()) {
  // At once, not a period later: the launcher's watchdog watches a process only once it has
  // reported, and a component stopped in its first second (the source was, by fault injection,
  // before its first tick) would otherwise never be seen hanging. Transient-local: a watchdog that
  // matches later still gets it.
  report(msg::ComponentState::STARTING);
}

void HealthReporter::frame_out(int64_t frame_index, double processing_ms, double latency_ms) {
  ++frames_out_;
  ++window_frames_;
  last_frame_ = frame_index;
  window_processing_ms_ += processing_ms;
  window_latency_ms_ += latency_ms;
  state_ = msg::ComponentState::RUNNING;
  // Report from here too: a busy node's take loop may not return to its outer loop (where it also
  // ticks) for as long as input keeps arriving, and its reports would stop exactly when it is the bottleneck.
  tick();
}

void HealthReporter::tick() {
  if (std::chrono::steady_clock::now() - last_report_ >= period_) report(state_);
}

void HealthReporter::report(msg::ComponentState state, const std::string& message) {
  const auto now = std::chrono::steady_clock::now();
  const double seconds = std::chrono::duration<double>(now - last_report_).count();
  state_ = state;
  msg::ComponentHealth sample;
  char host[64] = {};
  ::gethostname(host, sizeof(host) - 1);
  sample.stream_id(stream_id_);
  sample.component_name(component_);
  sample.host(host);
  sample.pid(static_cast<uint32_t>(::getpid()));
  sample.state(state);
  sample.stamp_ns(std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::system_clock::now().time_since_epoch()).count());
  sample.last_frame_index(last_frame_);
  const double n = static_cast<double>(window_frames_);
  sample.processing_ms(n > 0 ? window_processing_ms_ / n : 0.0);
  sample.latency_ms(n > 0 ? window_latency_ms_ / n : 0.0);
  sample.rate_hz(seconds > 0 ? n / seconds : 0.0);
  sample.queue_depth(queue_depth_);
  sample.frames_in(frames_in_);
  sample.frames_out(frames_out_);
  sample.dropped(dropped_);
  sample.invalid_samples(invalid_);
  sample.bytes_out(bytes_out_);
  sample.message(message.substr(0, 255));
  // One entry per topic name (a reader and a writer of the same name add up), at most 16.
  std::map<std::string, msg::TopicTraffic> traffic;
  for (const auto& [topic, add_counts] : watched_) {
    msg::TopicTraffic& t = traffic[topic];
    t.topic(topic.substr(0, 64));
    add_counts(t);
  }
  for (const auto& [topic, t] : traffic) {
    if (sample.topics().size() < 16) sample.topics().push_back(t);
  }
  writer_->write(sample);
  // The final state is what observers keep (status, tests): let it reach them before the process
  // goes, as the reliable writer disappears with its participant.
  if (state == msg::ComponentState::FINISHED || state == msg::ComponentState::FAILED) {
    writer_->native()->wait_for_acknowledgments(eprosima::fastrtps::Duration_t(1, 0));
  }
  last_report_ = now;
  window_frames_ = 0;
  window_processing_ms_ = window_latency_ms_ = 0.0;
}

}  // namespace uavmot::dds
