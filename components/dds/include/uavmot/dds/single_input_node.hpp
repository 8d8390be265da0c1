#pragma once
// The loop of a chain node with one input (motion: frames -> motion estimates): take, validate,
// process, publish, pass end-of-stream on, report health. Beside PairedNode, the loop of the
// nodes with two inputs; per-stream state lives in the caller's `process`.

#include <chrono>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>

#include "uavmot/core/shutdown.hpp"
#include "uavmot/dds/chain_convert.hpp"
#include "uavmot/dds/frame_convert.hpp"
#include "uavmot/dds/health_reporter.hpp"
#include "uavmot/dds/node_support.hpp"

namespace uavmot::dds {

template <class PubIn, class PubOut, class In>
class SingleInputNode {
 public:
  using Output = typename PubOut::type;
  // Returns the sample to publish, or nullopt to publish nothing for this input.
  using Process = std::function<std::optional<Output>(const std::string& stream, const In&)>;
  // Called once a frame's output is published (e.g. to save state that includes that frame).
  using Published = PublishedHook;

  struct Spec {
    std::string component;
    std::string input, output;
    TopicClass input_class;
    int streams = 1;           // exit after this many streams ended
    int required_readers = 0;  // lossless: readers of the output to wait for
    double upstream_timeout_s = 0.0;  // give up when no input has had a writer for this long (0: never)
  };

  SingleInputNode(Participant& participant, Spec spec, Process process, Published published = {})
      : spec_(std::move(spec)),
        mode_(participant.options().mode),
        reader_(participant.make_reader<PubIn>(spec_.input, spec_.input_class)),
        writer_(participant.make_writer<PubOut>(spec_.output, TopicClass::Chain)),
        health_(participant, spec_.component, "*"),
        ends_(spec_.streams),
        upstream_(spec_.upstream_timeout_s),
        process_(std::move(process)),
        published_(std::move(published)) {
    if (mode_ == DeliveryMode::Lossless) {
      writer_->set_required_readers(spec_.required_readers);
      writer_->exit_if_readers_never_match();
    }
    health_.watch(*reader_);
    health_.watch(*writer_);
  }

  int run() {
    spdlog::info("{} -> {} ({}, waiting for {} reader(s))", spec_.input, spec_.output, to_string(mode_),
                 spec_.required_readers);
    while (!shutdown_requested() && !ends_.all_ended()) {
      health_.set_queue_depth(static_cast<uint32_t>(reader_->unread()));
      health_.tick();
      if (!reader_->wait_for_data(std::chrono::milliseconds(200))) {
        if (upstream_.gone(reader_->matched())) return give_up_on_upstream(upstream_, health_, spec_.input);
        continue;
      }
      while (reader_->take(sample_)) handle(sample_);
    }
    writer_->flush(end_of_stream_patience(mode_));
    health_.report(msg::ComponentState::FINISHED);
    return 0;
  }

 private:
  // Frames are read in place (no copy of the pixels): `sample_` is not taken into again before
  // process() has returned.
  static std::optional<In> read(typename PubIn::type& sample, std::string& why) {
    if constexpr (std::is_same_v<typename PubIn::type, msg::Frame>) {
      return view_msg(sample, why);
    } else {
      return from_msg(sample, why);
    }
  }

  void handle(typename PubIn::type& sample) {
    const std::string stream = sample.stream_id().to_string();
    if (sample.end_of_stream()) {
      write_end_of_stream(*writer_, stream, sample.frame_index(), mode_);
      ends_.end(stream);
      return;
    }
    health_.frame_in();
    std::string why;
    auto value = read(sample, why);
    if (!value) {
      health_.invalid_sample();
      rejects_.log(spec_.input, why);
      return;
    }
    // Each stream's inputs come in frame order: a gap is frames the writer dropped (live mode); an
    // index seen already is a respawned writer sending its last sample again (it cannot know that
    // sample arrived), so it is skipped.
    const int64_t index = sample.frame_index();
    if (auto it = last_index_.find(stream); it != last_index_.end() && index <= it->second) {
      return;
    } else if (it != last_index_.end() && index > it->second + 1) {
      health_.dropped(static_cast<uint64_t>(index - it->second - 1));
    }
    last_index_[stream] = index;
    const auto t0 = std::chrono::steady_clock::now();
    auto out = process_(stream, *value);
    if (!out) return;
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    publish_frame_output(*writer_, *out, mode_, health_, published_, stream, index, ms, sample.capture_time_ns());
  }

  Spec spec_;
  DeliveryMode mode_;
  std::unique_ptr<TopicReader<PubIn>> reader_;
  std::unique_ptr<TopicWriter<PubOut>> writer_;
  HealthReporter health_;
  StreamEnds ends_;
  UpstreamWatch upstream_;
  RejectLog rejects_;
  Process process_;
  Published published_;
  std::map<std::string, int64_t> last_index_;
  typename PubIn::type sample_;  // reused: a frame sample keeps its pixel buffer between takes
};

}  // namespace uavmot::dds
