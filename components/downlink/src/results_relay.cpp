#include "uavmot/downlink/results_relay.hpp"

#include <algorithm>
#include <limits>

#include <spdlog/spdlog.h>

#include "uavmot/dds/chain_convert.hpp"

namespace uavmot::downlink {
namespace {

// Frames whose tracks have not come yet, per stream. Bounded: a tracker that stopped publishing
// must not make the downlink hoard (the oldest frame goes without tracks). In lossless mode every
// part comes, but motion runs ahead of segmentation and tracks by as much as their readers' queues
// hold (64 frames each) while the link holds the downlink back: the bound must be above that, or a
// frame would go without its regions (seen with the link down for 8 s).
constexpr size_t kMaxPendingFramesLive = 64;
constexpr size_t kMaxPendingFramesLossless = 1024;

// What the link does not carry need not wait in memory (dense features are most of a motion sample).
void strip(MotionEstimate& m) { m.features = {}; }
void strip(SegmentationResult& s) { s.clusters = {}; }
void strip(TrackList&) {}

dds::TopicClass inputs_of(bool resume) { return resume ? dds::TopicClass::ChainResume : dds::TopicClass::Chain; }

}  // namespace

ResultsRelay::ResultsRelay(dds::Participant& air, dds::Participant& link, int required_readers, dds::HealthReporter& health,
                           bool resume, const std::vector<std::string>& stream_ids)
    : mode_(link.options().mode),
      motion_(air.make_reader<msg::MotionEstimatePubSubType>(dds::kMotionTopic, inputs_of(resume), stream_ids)),
      segmentation_(air.make_reader<msg::SegmentationPubSubType>(dds::kSegmentationTopic, inputs_of(resume), stream_ids)),
      tracks_(air.make_reader<msg::TrackListPubSubType>(dds::kTracksTopic, inputs_of(resume), stream_ids)),
      writer_(link.make_writer<msg::FrameResultsPubSubType>(dds::kDownlinkResultsTopic, dds::TopicClass::Downlink)),
      health_(health) {
  if (mode_ == dds::DeliveryMode::Lossless) writer_->set_required_readers(required_readers);
  health_.watch(*motion_);
  health_.watch(*segmentation_);
  health_.watch(*tracks_);
  health_.watch(*writer_);
}

bool ResultsRelay::pump() {
  bool any = take(*motion_, &dds::FrameParts::motion);
  any |= take(*segmentation_, &dds::FrameParts::segmentation);
  any |= take(*tracks_, &dds::FrameParts::tracks);
  health_.set_queue_depth(static_cast<uint32_t>(motion_->unread() + segmentation_->unread() + tracks_->unread()));
  return any;
}

void ResultsRelay::log_link_changes() {
  const int matched = writer_->matched();
  if (matched == matched_) return;
  spdlog::info("{}: {} ground reader(s) {}", writer_->topic(), matched, matched > matched_ ? "matched" : "left");
  matched_ = matched;
}

template <class Reader, class Part>
bool ResultsRelay::take(Reader& reader, std::optional<Part> dds::FrameParts::*part) {
  typename Reader::Sample sample;
  bool any = false;
  while (reader.take(sample)) {
    any = true;
    const std::string id = sample.stream_id().to_string();
    StreamState& s = streams_[id];
    if (sample.end_of_stream()) {
      s.last_index = std::max(s.last_index, sample.frame_index());
      if (++s.ended_inputs == 3) end(id, s);
      continue;
    }
    std::string why;
    auto value = dds::from_msg(sample, why);
    if (!value) {
      health_.invalid_sample();
      rejects_.log(reader.topic(), why);
      continue;
    }
    const int64_t index = sample.frame_index();
    s.last_index = std::max(s.last_index, index);
    dds::FrameParts& frame = s.pending[index];
    strip(*value);
    frame.*part = std::move(*value);
    // Each input arrives in frame order, so once frame k is complete no earlier frame will get
    // another part: everything up to k can go.
    if (frame.motion && frame.segmentation && frame.tracks) {
      publish_up_to(id, s, index);
    } else if (s.pending.size() > (mode_ == dds::DeliveryMode::Lossless ? kMaxPendingFramesLossless : kMaxPendingFramesLive)) {
      publish_up_to(id, s, s.pending.begin()->first);
    }
  }
  return any;
}

// Publishes the pending frames up to `index`, in frame order.
void ResultsRelay::publish_up_to(const std::string& id, StreamState& s, int64_t index) {
  while (!s.pending.empty() && s.pending.begin()->first <= index) {
    auto node = s.pending.extract(s.pending.begin());
    auto sample = dds::to_downlink_msg(id, node.key(), node.mapped(), &drops_);
    if (!dds::publish(*writer_, sample, mode_)) health_.dropped();
    if (node.mapped().motion) health_.frame_in();
    health_.frame_out(node.key(), 0.0, dds::latency_ms_since(sample.capture_time_ns()));
  }
}

void ResultsRelay::end(const std::string& id, StreamState& s) {
  publish_up_to(id, s, std::numeric_limits<int64_t>::max());
  dds::write_end_of_stream(*writer_, id, std::max<int64_t>(s.last_index, 1), mode_);
  ++streams_ended_;
  spdlog::info("stream '{}' ended", id);
}

}  // namespace uavmot::downlink
