// uavmot-downlink: the UAV's gateway to the ground. It is the only air process on the radio
// link: it reads motion, segmentation and tracks on the UAV's own domain (shared memory, never on
// the link) and publishes on the link's domain, once per frame, what the ground uses:
//   uavmot/motion + uavmot/segmentation + uavmot/tracks -> uavmot/downlink/results
//       homography and quality, regions (as regions.txt prints them), tracks (float32, as the tracker rounds them); no features, clusters,
//       uncertainties or feature ids (idl/downlink.idl)
//   uavmot/health -> uavmot/health      the air components' reports, stream "*" -> --stream-id
//   uavmot/frames -> uavmot/downlink/preview   optional: JPEG, --preview-rate Hz, --preview-width px,
//                                              at most --preview-kbps (a flow controller)
// A frame's results go once its motion, segmentation and tracks are all there; a frame the chain
// skipped a part of (live mode) goes with what it has when a later frame is complete. The end of stream goes
// after all three inputs ended; it exits when every stream ended.
// The preview is best effort and newest-only: when the link is short of bandwidth it is the
// preview that loses images, never the results.

#include <cstdlib>
#include <limits>
#include <map>
#include <memory>

#include <opencv2/imgproc.hpp>
#include <spdlog/spdlog.h>

#include "downlinkPubSubTypes.h"
#include "framePubSubTypes.h"
#include "healthPubSubTypes.h"
#include "motionPubSubTypes.h"
#include "segmentationPubSubTypes.h"
#include "tracksPubSubTypes.h"
#include "uavmot/core/app.hpp"
#include "uavmot/core/error.hpp"
#include "uavmot/core/shutdown.hpp"
#include "uavmot/dds/chain_convert.hpp"
#include "uavmot/dds/downlink_convert.hpp"
#include "uavmot/dds/frame_convert.hpp"
#include "uavmot/dds/health_reporter.hpp"
#include "uavmot/dds/node_options.hpp"
#include "uavmot/dds/node_support.hpp"

namespace uavmot {
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

struct StreamState {
  std::map<int64_t, dds::FrameParts> pending;
  int ended_inputs = 0;  // of motion, segmentation, tracks
  int64_t last_index = 0;
};

class Results {
 public:
  Results(dds::Participant& air, dds::Participant& link, int required_readers, dds::HealthReporter& health)
      : mode_(link.options().mode),
        motion_(air.make_reader<msg::MotionEstimatePubSubType>(dds::kMotionTopic, dds::TopicClass::Chain)),
        segmentation_(air.make_reader<msg::SegmentationPubSubType>(dds::kSegmentationTopic, dds::TopicClass::Chain)),
        tracks_(air.make_reader<msg::TrackListPubSubType>(dds::kTracksTopic, dds::TopicClass::Chain)),
        writer_(link.make_writer<msg::FrameResultsPubSubType>(dds::kDownlinkResultsTopic, dds::TopicClass::Downlink)),
        health_(health) {
    if (mode_ == dds::DeliveryMode::Lossless) writer_->set_required_readers(required_readers);
    health_.watch(*motion_);
    health_.watch(*segmentation_);
    health_.watch(*tracks_);
    health_.watch(*writer_);
  }

  // Takes what waits on the three inputs and publishes every frame that is complete. True if any was taken.
  bool pump() {
    bool any = take(*motion_, &dds::FrameParts::motion);
    any |= take(*segmentation_, &dds::FrameParts::segmentation);
    any |= take(*tracks_, &dds::FrameParts::tracks);
    health_.set_queue_depth(static_cast<uint32_t>(motion_->unread() + segmentation_->unread() + tracks_->unread()));
    return any;
  }

  int streams_ended() const { return streams_ended_; }
  const dds::DownlinkDrops& drops() const { return drops_; }
  dds::TopicWriter<msg::FrameResultsPubSubType>& writer() { return *writer_; }
  dds::TopicReader<msg::TrackListPubSubType>& tracks() { return *tracks_; }

  // Logs when the link's reader comes and goes (the link dropped, the ground restarted).
  void log_link_changes() {
    const int matched = writer_->matched();
    if (matched == matched_) return;
    spdlog::info("{}: {} ground reader(s) {}", writer_->topic(), matched, matched > matched_ ? "matched" : "left");
    matched_ = matched;
  }

 private:
  template <class Reader, class Part>
  bool take(Reader& reader, std::optional<Part> dds::FrameParts::*part) {
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
  void publish_up_to(const std::string& id, StreamState& s, int64_t index) {
    while (!s.pending.empty() && s.pending.begin()->first <= index) {
      auto node = s.pending.extract(s.pending.begin());
      auto sample = dds::to_downlink_msg(id, node.key(), node.mapped(), &drops_);
      if (!dds::publish(*writer_, sample, mode_)) health_.dropped();
      if (node.mapped().motion) health_.frame_in();
      health_.frame_out(node.key(), 0.0, dds::latency_ms_since(sample.capture_time_ns()));
    }
  }

  void end(const std::string& id, StreamState& s) {
    publish_up_to(id, s, std::numeric_limits<int64_t>::max());
    msg::FrameResults eos;
    eos.stream_id(id);
    eos.frame_index(std::max<int64_t>(s.last_index, 1));
    eos.end_of_stream(true);
    writer_->write_reliably(eos, dds::end_of_stream_patience(mode_));
    ++streams_ended_;
    spdlog::info("stream '{}' ended", id);
  }

  dds::DeliveryMode mode_;
  std::unique_ptr<dds::TopicReader<msg::MotionEstimatePubSubType>> motion_;
  std::unique_ptr<dds::TopicReader<msg::SegmentationPubSubType>> segmentation_;
  std::unique_ptr<dds::TopicReader<msg::TrackListPubSubType>> tracks_;
  std::unique_ptr<dds::TopicWriter<msg::FrameResultsPubSubType>> writer_;
  dds::HealthReporter& health_;
  dds::RejectLog rejects_;
  std::map<std::string, StreamState> streams_;
  int streams_ended_ = 0;
  dds::DownlinkDrops drops_;
  int matched_ = 0;
};

struct PreviewOptions {
  double rate_hz = 0.0;  // 0: no preview
  int width = 320;       // px; the height keeps the aspect ratio
  int quality = 75;      // JPEG
  double kbps = 500.0;   // flow controller limit; 0: none
};

// Every 1/rate s, the newest frame as a small JPEG on the link, but never faster than its share
// lets an image through: a newer image would replace the one the flow controller is still
// sending (newest only), and none would ever arrive. Frames due while the previous image still
// uses the share are skipped: the preview gives way; the flow controller is the hard cap.
class Preview {
 public:
  static constexpr const char* kFlow = "uavmot_preview";

  Preview(dds::Participant& air, dds::Participant& link, const PreviewOptions& o)
      : options_(o),
        frames_(air.make_reader<msg::FramePubSubType>(dds::kFramesTopic, dds::TopicClass::Preview)),
        writer_(link.make_writer<msg::FramePubSubType>(dds::kDownlinkPreviewTopic, dds::TopicClass::Preview,
                                                       o.kbps > 0 ? kFlow : "")) {}

  void pump(dds::HealthReporter& health) {
    using Clock = std::chrono::steady_clock;
    msg::Frame sample;
    while (frames_->take(sample)) {
      const auto now = Clock::now();
      if (sample.end_of_stream() || now < next_due_) continue;
      next_due_ = now + seconds(1.0 / options_.rate_hz);
      ++due_;
      if (now < share_free_) continue;  // the last image still needs the share
      std::string why;
      auto frame = dds::from_msg(sample, why);
      if (!frame) {
        health.invalid_sample();
        continue;
      }
      if (frame->image.cols > options_.width) {
        const int height = std::max(1, frame->image.rows * options_.width / frame->image.cols);
        cv::resize(frame->image, frame->image, cv::Size(options_.width, height), 0, 0, cv::INTER_AREA);
      }
      auto jpeg = dds::to_jpeg_msg(*frame, options_.quality);
      if (options_.kbps > 0) share_free_ = now + seconds(static_cast<double>(jpeg.data().size()) * 8.0 / (options_.kbps * 1000.0));
      writer_->write(jpeg);
    }
  }

  uint64_t due() const { return due_; }
  dds::TopicReader<msg::FramePubSubType>& frames() { return *frames_; }
  dds::TopicWriter<msg::FramePubSubType>& writer() { return *writer_; }

 private:
  static std::chrono::steady_clock::duration seconds(double s) {
    return std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(s));
  }

  PreviewOptions options_;
  std::unique_ptr<dds::TopicReader<msg::FramePubSubType>> frames_;
  std::unique_ptr<dds::TopicWriter<msg::FramePubSubType>> writer_;
  std::chrono::steady_clock::time_point next_due_{}, share_free_{};
  uint64_t due_ = 0;
};

int downlink_main(int argc, char** argv) {
  dds::NodeOptions node;  // the link: --domain, --transport (udp), --mode, --wait-subscribers (ground readers)
  int air_domain = 1;
  std::string air_transport = "shm", stream_id = "*";
  int streams = 1;
  PreviewOptions preview_options;
  return run_app(argc, argv, "downlink", "relay the chain's results to the ground in compact form (air -> link)", [&](CLI::App& app) {
    app.add_option("--air-domain", air_domain, "DDS domain of the UAV's own processes")->check(CLI::Range(0, 232))->capture_default_str();
    app.add_option("--air-transport", air_transport, "participant profile on the UAV's side (shm: never on the link)")
        ->capture_default_str();
    app.add_option("--stream-id", stream_id, "this UAV's stream: health reports of nodes serving every stream (\"*\") get it")
        ->capture_default_str();
    app.add_option("--streams", streams, "exit after this many streams ended")->check(CLI::PositiveNumber)->capture_default_str();
    app.add_option("--preview-rate", preview_options.rate_hz, "JPEG previews of the frames per second (0: none)")
        ->check(CLI::NonNegativeNumber)->capture_default_str();
    app.add_option("--preview-width", preview_options.width, "preview width, px (height keeps the aspect ratio)")
        ->check(CLI::Range(16, 8192))->capture_default_str();
    app.add_option("--preview-quality", preview_options.quality, "preview JPEG quality")->check(CLI::Range(1, 100))->capture_default_str();
    app.add_option("--preview-kbps", preview_options.kbps, "the preview's share of the link, kbit/s (a flow controller; 0: unlimited)")
        ->check(CLI::NonNegativeNumber)->capture_default_str();
    node.dds.participant_profile = "udp";
    dds::add_node_options(app, node);
    return [&]() -> int {
      dds::finalize(node, "downlink");
      install_shutdown_handler();
      if (air_domain == node.dds.domain_id && air_transport == node.dds.participant_profile) {
        throw InputError("--air-domain and --domain must differ when both sides use the same transport");
      }
      // Only the link uses the discovery server: Fast DDS would turn every participant of this
      // process into a client of $ROS_DISCOVERY_SERVER, the shared-memory one too, which would then
      // never meet the UAV's processes.
      if (const char* env = std::getenv("ROS_DISCOVERY_SERVER")) {
        if (node.dds.discovery_server.empty()) node.dds.discovery_server = env;
        ::unsetenv("ROS_DISCOVERY_SERVER");
      }
      dds::DdsOptions air_options = node.dds;
      air_options.discovery_server.clear();
      air_options.domain_id = air_domain;
      air_options.participant_profile = air_transport;
      air_options.participant_name = "downlink-air";
      if (preview_options.rate_hz > 0 && preview_options.kbps > 0) {
        node.dds.flow_limits.push_back({Preview::kFlow, static_cast<uint64_t>(preview_options.kbps * 1000.0)});
      }
      dds::Participant air(air_options);
      dds::Participant link(node.dds);

      dds::HealthReporter health(link, "downlink", stream_id);
      Results results(air, link, node.wait_subscribers, health);
      auto air_health = air.make_reader<msg::ComponentHealthPubSubType>(dds::kHealthTopic, dds::TopicClass::Health);
      auto link_health = link.make_writer<msg::ComponentHealthPubSubType>(dds::kHealthTopic, dds::TopicClass::Health);
      health.watch(*air_health);
      health.watch(*link_health);
      std::unique_ptr<Preview> preview;
      if (preview_options.rate_hz > 0) {
        preview = std::make_unique<Preview>(air, link, preview_options);
        health.watch(preview->frames());
        health.watch(preview->writer());
        spdlog::info("preview: {} Hz, {} px wide, at most {} kbit/s", preview_options.rate_hz, preview_options.width,
                     preview_options.kbps);
      }
      spdlog::info("domain {} ({}) -> domain {} ({}), {}, waiting for {} ground reader(s)", air_domain, air_transport,
                   node.dds.domain_id, node.dds.participant_profile, node.mode, node.wait_subscribers);

      while (!shutdown_requested() && results.streams_ended() < streams) {
        const bool any = results.pump();
        msg::ComponentHealth report;
        while (air_health->take(report)) {
          if (report.stream_id().to_string() == "*") report.stream_id(stream_id);
          link_health->write(report);
        }
        if (preview) preview->pump(health);
        results.log_link_changes();
        health.set_bytes_out(results.writer().bytes_sent());
        health.tick();
        if (!any) results.tracks().wait_for_data(std::chrono::milliseconds(50));
      }
      // Every frame before the end of stream was acknowledged before the next was written
      // (lossless); only the end of stream itself may be unacknowledged when the ground's reader
      // exits right after reading it, which the writer learns only when that reader's participant
      // is gone. So: a short wait, and no failure.
      if (!results.writer().flush(std::chrono::seconds(5))) spdlog::warn("end of stream not acknowledged (the reader left?)");
      auto sent = [](const auto& w) { spdlog::info("{}: {} samples, {} bytes", w.topic(), w.samples_sent(), w.bytes_sent()); };
      sent(results.writer());
      sent(*link_health);
      if (preview) {
        sent(preview->writer());
        spdlog::info("preview: {} of {} images due at {} Hz sent (the rest gave way to the {} kbit/s share)",
                     preview->writer().samples_sent(), preview->due(), preview_options.rate_hz, preview_options.kbps);
      }
      if (results.drops().tracks > 0) spdlog::warn("{} tracks had ids beyond 32 bits and were not sent", results.drops().tracks);
      if (results.drops().inexact_tracks > 0) {
        spdlog::warn("{} tracks were not float32 values and were sent rounded (not from uavmot's tracker?)",
                     results.drops().inexact_tracks);
      }
      if (results.drops().regions > 0) spdlog::warn("{} regions did not fit the compact fields and were not sent", results.drops().regions);
      health.report(msg::ComponentState::FINISHED);
      return results.streams_ended() >= streams ? kExitOk : kExitFailure;
    };
  });
}

}  // namespace
}  // namespace uavmot

int main(int argc, char** argv) { return uavmot::downlink_main(argc, argv); }
