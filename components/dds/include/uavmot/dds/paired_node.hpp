#pragma once
// The loop of a chain node with two inputs joined by frame index (segmentation: frames + motion;
// tracking: motion + segmentation): take, validate, pair in frame order, process, publish,
// pass end-of-stream on, report health. Per-stream state lives in the caller's `process`.

#include <chrono>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include "uavmot/core/frame_pairing.hpp"
#include "uavmot/core/shutdown.hpp"
#include "uavmot/dds/chain_convert.hpp"
#include "uavmot/dds/frame_convert.hpp"
#include "uavmot/dds/health_reporter.hpp"
#include "uavmot/dds/node_support.hpp"

namespace uavmot::dds {

template <class PubA, class PubB, class PubOut, class A, class B>
class PairedNode {
 public:
  // Returns the sample to publish, or nullopt to publish nothing for this pair.
  using Process = std::function<std::optional<typename PubOut::type>(const std::string& stream, int64_t index, const A&, const B&)>;
  // Called after the sample of (stream, index) was published (e.g. to save state only once its
  // output is out: a restart then redoes at most a frame whose output readers may already have).
  using Published = PublishedHook;

  struct Spec {
    std::string component;
    std::string input_a, input_b, output;
    TopicClass class_a, class_b;
    int streams = 1;
    int required_readers = 0;  // lossless: readers of the output to wait for
    double upstream_timeout_s = 0.0;  // give up when no input has had a writer for this long (0: never)
  };

  PairedNode(Participant& participant, Spec spec, Process process, Published published = {})
      : spec_(std::move(spec)),
        mode_(participant.options().mode),
        reader_a_(participant.make_reader<PubA>(spec_.input_a, spec_.class_a)),
        reader_b_(participant.make_reader<PubB>(spec_.input_b, spec_.class_b)),
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
    health_.watch(*reader_a_);
    health_.watch(*reader_b_);
    health_.watch(*writer_);
  }

  int run() {
    spdlog::info("{} + {} -> {} ({}, waiting for {} reader(s))", spec_.input_a, spec_.input_b, spec_.output,
                 to_string(mode_), spec_.required_readers);
    while (!shutdown_requested() && !ends_.all_ended()) {
      health_.set_queue_depth(static_cast<uint32_t>(reader_a_->unread() + reader_b_->unread()));
      health_.tick();
      bool any = take_all(*reader_a_, true, sample_a_) | take_all(*reader_b_, false, sample_b_);
      if (!any) {
        if (upstream_.gone(reader_a_->matched() + reader_b_->matched())) {
          return give_up_on_upstream(upstream_, health_, spec_.input_a + " and " + spec_.input_b);
        }
        // Wait on the side that is behind (either would do; this keeps the wakeups few).
        reader_b_->wait_for_data(std::chrono::milliseconds(50));
        reader_a_->wait_for_data(std::chrono::milliseconds(1));
      }
    }
    writer_->flush(end_of_stream_patience(mode_));
    health_.report(msg::ComponentState::FINISHED);
    return 0;
  }

 private:
  struct StreamState {
    FramePairing<A, B> pairing;
    bool ended_a = false, ended_b = false;
    int64_t last_index = 0;
  };

  StreamState& stream(const std::string& id) {
    return streams_[id];
  }

  // `sample` is a member, reused: a frame sample keeps its pixel buffer between takes.
  template <class Reader>
  bool take_all(Reader& reader, bool is_a, typename Reader::Sample& sample) {
    bool any = false;
    while (reader.take(sample)) {
      any = true;
      const std::string id = sample.stream_id().to_string();
      StreamState& s = stream(id);
      if (sample.end_of_stream()) {
        (is_a ? s.ended_a : s.ended_b) = true;
        s.last_index = std::max(s.last_index, sample.frame_index());
      } else {
        if (is_a) health_.frame_in();
        std::string why;
        auto value = from_msg(sample, why);
        if (!value) {
          health_.invalid_sample();
          rejects_.log(reader.topic(), why);
          continue;
        }
        if constexpr (std::is_same_v<typename Reader::Sample, typename PubA::type>) {
          if (is_a) s.pairing.add_first(sample.frame_index(), std::move(*value));
        }
        if constexpr (std::is_same_v<typename Reader::Sample, typename PubB::type>) {
          if (!is_a) s.pairing.add_second(sample.frame_index(), std::move(*value));
        }
      }
      drain(id, s);
    }
    return any;
  }

  void drain(const std::string& id, StreamState& s) {
    const uint64_t dropped_before = s.pairing.dropped();
    while (auto pair = s.pairing.pop()) {
      const auto t0 = std::chrono::steady_clock::now();
      auto out = process_(id, pair->index, pair->first, pair->second);
      if (!out) continue;
      const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      publish_frame_output(*writer_, *out, mode_, health_, published_, id, pair->index, ms, out->capture_time_ns());
    }
    health_.dropped(s.pairing.dropped() - dropped_before);
    if (s.ended_a && s.ended_b && !ends_.ended(id)) {
      // Both inputs ended: whatever is still unpaired can never complete.
      health_.dropped(s.pairing.pending());
      write_end_of_stream(*writer_, id, s.last_index, mode_);
      ends_.end(id);
    }
  }

  Spec spec_;
  DeliveryMode mode_;
  std::unique_ptr<TopicReader<PubA>> reader_a_;
  std::unique_ptr<TopicReader<PubB>> reader_b_;
  std::unique_ptr<TopicWriter<PubOut>> writer_;
  HealthReporter health_;
  StreamEnds ends_;
  UpstreamWatch upstream_;
  RejectLog rejects_;
  Process process_;
  Published published_;
  std::map<std::string, StreamState> streams_;
  typename PubA::type sample_a_;
  typename PubB::type sample_b_;
};

}  // namespace uavmot::dds
