// uavmot-downlink: the UAV's gateway to the ground. It is the only air process on the radio
// link: it reads motion, segmentation and tracks on the UAV's own domain (shared memory, never on
// the link) and publishes on the link's domain what the ground uses, once per frame:
//   uavmot/motion       -> uavmot/downlink/motion    homography and quality, no features
//   uavmot/segmentation -> uavmot/downlink/regions   regions in float32, no clusters
//   uavmot/tracks       -> uavmot/downlink/tracks    boxes and velocities in float32
//   uavmot/health       -> uavmot/health             the air components' reports, stream "*" -> --stream-id
//   uavmot/frames       -> uavmot/downlink/preview   optional: JPEG, --preview-rate Hz, --preview-width px,
//                                                    at most --preview-kbps (a flow controller)
// End of stream is passed on per topic; it exits when every stream ended on all three.
// The preview is best effort and newest-only: when the link is short of bandwidth it is the
// preview that loses images, never the results.

#include <cstdlib>
#include <map>
#include <memory>
#include <set>

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

// One chain topic on the air side -> its compact variant on the link.
template <class InPub, class OutPub>
class Relay {
 public:
  Relay(dds::Participant& air, dds::Participant& link, const char* in_topic, const char* out_topic, int required_readers)
      : mode_(link.options().mode),
        reader_(air.make_reader<InPub>(in_topic, dds::TopicClass::Chain)),
        writer_(link.make_writer<OutPub>(out_topic, dds::TopicClass::Downlink)) {
    if (mode_ == dds::DeliveryMode::Lossless) writer_->set_required_readers(required_readers);
  }

  // Publishes every sample waiting; calls `ended(stream)` at each end of stream. True if any was taken.
  template <class OnFrame, class OnEnd>
  bool pump(dds::HealthReporter& health, dds::RejectLog& rejects, OnFrame on_frame, OnEnd ended) {
    typename InPub::type sample;
    bool any = false;
    while (reader_->take(sample)) {
      any = true;
      const std::string stream = sample.stream_id().to_string();
      if (sample.end_of_stream()) {
        typename OutPub::type eos;
        eos.stream_id(stream);
        eos.frame_index(sample.frame_index());
        eos.end_of_stream(true);
        writer_->write_reliably(eos, dds::end_of_stream_patience(mode_));
        if (ended_.insert(stream).second) ended(stream);
        continue;
      }
      std::string why;
      auto value = dds::from_msg(sample, why);
      if (!value) {
        health.invalid_sample();
        rejects.log(reader_->topic(), why);
        continue;
      }
      auto out = dds::to_downlink_msg(*value);
      if (!dds::publish(*writer_, out, mode_)) health.dropped();
      on_frame(*value);
    }
    return any;
  }

  // Logs when the link's readers come and go (the link dropped, the ground restarted).
  void log_link_changes() {
    const int matched = writer_->matched();
    if (matched == matched_) return;
    spdlog::info("{}: {} ground reader(s) {}", writer_->topic(), matched, matched > matched_ ? "matched" : "left");
    matched_ = matched;
  }

  // Every sample before the end of stream was acknowledged before it was written (lossless); only
  // the end of stream itself may be unacknowledged when the ground's reader exits right after
  // reading it, which the writer learns only when that reader's participant is gone. So: a short
  // wait, and no failure.
  void flush() {
    if (!writer_->flush(std::chrono::seconds(5))) spdlog::warn("{}: end of stream not acknowledged (the reader left?)", writer_->topic());
  }
  dds::TopicReader<InPub>& reader() { return *reader_; }
  dds::TopicWriter<OutPub>& writer() { return *writer_; }

 private:
  dds::DeliveryMode mode_;
  std::unique_ptr<dds::TopicReader<InPub>> reader_;
  std::unique_ptr<dds::TopicWriter<OutPub>> writer_;
  std::set<std::string> ended_;
  int matched_ = 0;
};

struct PreviewOptions {
  double rate_hz = 0.0;  // 0: no preview
  int width = 320;       // px; the height keeps the aspect ratio
  int quality = 75;      // JPEG
  double kbps = 500.0;   // flow controller limit; 0: none
};

// Every 1/rate s, the newest frame as a small JPEG on the link.
class Preview {
 public:
  static constexpr const char* kFlow = "uavmot_preview";

  Preview(dds::Participant& air, dds::Participant& link, const PreviewOptions& o)
      : options_(o),
        frames_(air.make_reader<msg::FramePubSubType>(dds::kFramesTopic, dds::TopicClass::Preview)),
        writer_(link.make_writer<msg::FramePubSubType>(dds::kDownlinkPreviewTopic, dds::TopicClass::Preview,
                                                       o.kbps > 0 ? kFlow : "")) {}

  void pump(dds::HealthReporter& health) {
    msg::Frame sample;
    while (frames_->take(sample)) {
      if (sample.end_of_stream()) continue;
      const auto now = std::chrono::steady_clock::now();
      if (now < next_) continue;
      next_ = now + std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(1.0 / options_.rate_hz));
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
      writer_->write(jpeg);
    }
  }

  dds::TopicReader<msg::FramePubSubType>& frames() { return *frames_; }
  dds::TopicWriter<msg::FramePubSubType>& writer() { return *writer_; }

 private:
  PreviewOptions options_;
  std::unique_ptr<dds::TopicReader<msg::FramePubSubType>> frames_;
  std::unique_ptr<dds::TopicWriter<msg::FramePubSubType>> writer_;
  std::chrono::steady_clock::time_point next_{};
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

      const int readers = node.wait_subscribers;
      Relay<msg::MotionEstimatePubSubType, msg::MotionSummaryPubSubType> motion(air, link, dds::kMotionTopic,
                                                                                 dds::kDownlinkMotionTopic, readers);
      Relay<msg::SegmentationPubSubType, msg::RegionListPubSubType> regions(air, link, dds::kSegmentationTopic,
                                                                             dds::kDownlinkRegionsTopic, readers);
      Relay<msg::TrackListPubSubType, msg::CompactTrackListPubSubType> tracks(air, link, dds::kTracksTopic,
                                                                               dds::kDownlinkTracksTopic, readers);
      auto air_health = air.make_reader<msg::ComponentHealthPubSubType>(dds::kHealthTopic, dds::TopicClass::Health);
      auto link_health = link.make_writer<msg::ComponentHealthPubSubType>(dds::kHealthTopic, dds::TopicClass::Health);
      dds::HealthReporter health(link, "downlink", stream_id);
      health.watch(motion.reader());
      health.watch(regions.reader());
      health.watch(tracks.reader());
      health.watch(*air_health);
      health.watch(motion.writer());
      health.watch(regions.writer());
      health.watch(tracks.writer());
      health.watch(*link_health);
      std::unique_ptr<Preview> preview;
      if (preview_options.rate_hz > 0) {
        preview = std::make_unique<Preview>(air, link, preview_options);
        health.watch(preview->frames());
        health.watch(preview->writer());
        spdlog::info("preview: {} Hz, {} px wide, at most {} kbit/s", preview_options.rate_hz, preview_options.width,
                     preview_options.kbps);
      }
      dds::RejectLog rejects;
      std::map<std::string, int> topics_ended;  // per stream: how many of the three topics ended
      int streams_ended = 0;
      auto ended = [&](const std::string& stream) {
        if (++topics_ended[stream] == 3) {
          ++streams_ended;
          spdlog::info("stream '{}' ended", stream);
        }
      };
      spdlog::info("domain {} ({}) -> domain {} ({}), {}, waiting for {} ground reader(s)", air_domain, air_transport,
                   node.dds.domain_id, node.dds.participant_profile, node.mode, readers);

      while (!shutdown_requested() && streams_ended < streams) {
        bool any = motion.pump(health, rejects, [&](const MotionEstimate&) { health.frame_in(); }, ended);
        any |= regions.pump(health, rejects, [](const SegmentationResult&) {}, ended);
        any |= tracks.pump(health, rejects, [&](const TrackList& t) {
          health.frame_out(t.frame_index, 0.0, dds::latency_ms_since(t.capture_time_ns));
        }, ended);
        msg::ComponentHealth report;
        while (air_health->take(report)) {
          if (report.stream_id().to_string() == "*") report.stream_id(stream_id);
          link_health->write(report);
        }
        if (preview) preview->pump(health);
        motion.log_link_changes();
        regions.log_link_changes();
        tracks.log_link_changes();
        health.set_queue_depth(static_cast<uint32_t>(motion.reader().unread() + regions.reader().unread() +
                                                     tracks.reader().unread()));
        health.set_bytes_out(motion.writer().bytes_sent() + regions.writer().bytes_sent() + tracks.writer().bytes_sent());
        health.tick();
        if (!any) tracks.reader().wait_for_data(std::chrono::milliseconds(50));
      }
      motion.flush();
      regions.flush();
      tracks.flush();
      auto sent = [](const auto& w) {
        spdlog::info("{}: {} samples, {} bytes", w.topic(), w.samples_sent(), w.bytes_sent());
      };
      sent(motion.writer());
      sent(regions.writer());
      sent(tracks.writer());
      sent(*link_health);
      if (preview) sent(preview->writer());
      health.report(msg::ComponentState::FINISHED);
      return streams_ended >= streams ? kExitOk : kExitFailure;
    };
  });
}

}  // namespace
}  // namespace uavmot

int main(int argc, char** argv) { return uavmot::downlink_main(argc, argv); }
