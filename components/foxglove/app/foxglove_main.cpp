// uavmot-foxglove: the live bridge for Foxglove on the ground station (docs/foxglove.md). Reads the
// chain's topics with best-effort readers (the chain never waits for it) and serves them over the
// Foxglove WebSocket protocol: each uavmot topic as its own type (omgidl + cdr), plus the
// Foxglove-schema image and annotation channels the Image panel draws. Any number of viewers; a
// slow one loses messages, nobody else does.

#include <algorithm>
#include <chrono>
#include <memory>
#include <set>
#include <thread>

#include "downlinkPubSubTypes.h"
#include "framePubSubTypes.h"
#include "healthPubSubTypes.h"

#include <spdlog/spdlog.h>

#include "uavmot/core/app.hpp"
#include "uavmot/core/cpu_priority.hpp"
#include "uavmot/core/error.hpp"
#include "uavmot/core/shutdown.hpp"
#include "uavmot/dds/node_options.hpp"
#include "uavmot/foxglove/schemas.hpp"
#include "uavmot/foxglove/ws_server.hpp"
#include "uavmot/dds/cdr_sample.hpp"
#include "uavmot/record/foxglove_translation.hpp"
#include "uavmot/record/topic_catalog.hpp"
#include "uavmot/record/typed_topic.hpp"

namespace uavmot {
namespace {

uint64_t wall_ns() {
  return static_cast<uint64_t>(
      std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::system_clock::now().time_since_epoch()).count());
}

// Lossless chains: a writer starts publishing once its --wait-subscribers readers are matched, and
// Fast DDS 2.9 cannot tell it which of them are reliable, so a best-effort bridge reader would count
// and let it start before a lossless reader (the sink, the recorder) is there. In lossless mode the
// bridge therefore subscribes to a chain topic only once the component writing it has reported on
// the health topic that it published (it is past its wait; a later respawn is not covered).
class WriterStarts {
 public:
  explicit WriterStarts(dds::Participant& participant)
      : reader_(participant.make_reader<msg::ComponentHealthPubSubType>(dds::kHealthTopic, dds::TopicClass::Health)) {}
  void update() {
    while (reader_->take(sample_)) {
      if (sample_.frames_out() > 0) started_.insert(sample_.component_name().to_string());
    }
  }
  bool started(const std::string& component) const { return started_.count(component) > 0; }

 private:
  std::unique_ptr<dds::TopicReader<msg::ComponentHealthPubSubType>> reader_;
  msg::ComponentHealth sample_;
  std::set<std::string> started_;
};

// The component that writes a chain topic, as it names itself on the health topic.
std::string writer_component(const std::string& topic) {
  if (topic == dds::kFramesTopic) return "source";
  if (topic == dds::kMotionTopic) return "motion";
  if (topic == dds::kSegmentationTopic) return "segmentation";
  if (topic == dds::kTracksTopic) return "tracking";
  return "";  // the link's topics: their writer's health may be on the UAV's domain, not the link's
}

class TopicBridge {
 public:
  virtual ~TopicBridge() = default;
  virtual size_t drain() = 0;  // takes every waiting sample, serves it; returns how many
  virtual bool reading() const = 0;  // has a reader (some viewer watches the topic)
  virtual bool wait_for_data(std::chrono::milliseconds timeout) = 0;
  uint64_t invalid() const { return invalid_; }

 protected:
  uint64_t invalid_ = 0;
};

template <class PubSubType>
class TypedBridge final : public TopicBridge {
 public:
  // `starts`: subscribe only once the topic's writer has published (lossless chains); null: at once.
  // `image_interval_ns`: the least time between two encoded images of the frames topic (0: every frame).
  TypedBridge(dds::Participant& participant, const record::TopicSpec& spec, const std::string& idl_dir,
              const record::FoxgloveOptions& options, foxglove::WsServer& server, const WriterStarts* starts,
              uint64_t image_interval_ns)
      : participant_(participant), spec_(spec), starts_(starts), options_(options), server_(server),
        image_interval_ns_(spec.topic == dds::kFramesTopic ? image_interval_ns : 0) {
    raw_channel_ = server_.add_channel({spec.topic, "cdr", spec.type_name, record::schema_text(spec, idl_dir), "omgidl"});
    if (const auto fc = record::foxglove_channel(spec.topic, options)) {
      foxglove_channel_ = server_.add_channel(
          {fc->topic, "cdr", fc->schema_name, foxglove::schema_text(fc->schema_name, idl_dir), "omgidl"});
    }
  }

  size_t drain() override {
    // A topic is read only while a viewer watches one of its channels: with no viewer the bridge
    // has no reader on the chain's topics at all, so the chain's writers have nobody extra to serve.
    // Asked once a drain: a viewer that subscribes meanwhile gets the samples of the next one.
    const bool raw_watched = server_.has_subscribers(raw_channel_);
    const bool foxglove_watched = foxglove_channel_ && server_.has_subscribers(foxglove_channel_);
    if (!raw_watched && !foxglove_watched) {
      if (reader_) {
        participant_.delete_reader(std::move(reader_));
        spdlog::info("foxglove: no viewer watches {}; reader closed", spec_.topic);
      }
      return 0;
    }
    if (!reader_) {
      const std::string writer = writer_component(spec_.topic);
      if (starts_ && !writer.empty() && !starts_->started(writer)) return 0;
      subscribe();
      spdlog::info("foxglove: a viewer watches {}; subscribing", spec_.topic);
    }
    size_t n = 0;
    while (reader_->take(sample_)) {
      ++n;
      const uint64_t received = wall_ns();
      // Work only for channels somebody watches: with no viewer the bridge costs a take().
      if (raw_watched) {
        const auto bytes = dds::to_cdr(type_, sample_);
        server_.publish(raw_channel_, received, bytes.data(), bytes.size());
      }
      if (foxglove_watched && image_due(received)) {
        std::string why;
        if (const auto bytes = record::to_foxglove(sample_, options_, why)) {
          server_.publish(foxglove_channel_, received, bytes->data(), bytes->size());
        } else if (!why.empty()) {
          ++invalid_;
          spdlog::warn("{}: {}", reader_->topic(), why);
        }
      }
    }
    return n;
  }
  bool reading() const override { return reader_ != nullptr; }
  bool wait_for_data(std::chrono::milliseconds timeout) override { return reader_ && reader_->wait_for_data(timeout); }

 private:
  void subscribe() {
    reader_ = spec_.topic_class == dds::TopicClass::Health || spec_.topic_class == dds::TopicClass::Preview
                  ? participant_.make_reader<PubSubType>(spec_.topic, spec_.topic_class)
                  : participant_.make_reader<PubSubType>(spec_.topic, std::string("bridge_reader"));
  }

  // Encoding a frame as JPEG is the one costly step of the bridge (~4 ms at 1024 x 768, on the
  // chain's own cores in a one-box deployment): a person watching needs no 25 images a second.
  bool image_due(uint64_t now_ns) {
    if (image_interval_ns_ == 0) return true;
    if (last_image_ns_ != 0 && now_ns - last_image_ns_ < image_interval_ns_) return false;
    last_image_ns_ = now_ns;
    return true;
  }

  dds::Participant& participant_;
  record::TopicSpec spec_;
  const WriterStarts* starts_;
  std::unique_ptr<dds::TopicReader<PubSubType>> reader_;
  record::FoxgloveOptions options_;
  foxglove::WsServer& server_;
  PubSubType type_;
  typename PubSubType::type sample_;
  uint32_t raw_channel_ = 0, foxglove_channel_ = 0;
  uint64_t image_interval_ns_ = 0, last_image_ns_ = 0;
};

// The air -> ground link's topics (docs/deployment.md), served with --downlink on the ground station.
const std::vector<record::TopicSpec>& link_topics() {
  static const std::vector<record::TopicSpec> topics = {
      {dds::kDownlinkResultsTopic, "uavmot::msg::FrameResults", "downlink.idl", dds::TopicClass::Downlink},
      {dds::kDownlinkPreviewTopic, "uavmot::msg::Frame", "frame.idl", dds::TopicClass::Preview},
      *record::find_topic(dds::kHealthTopic),
  };
  return topics;
}

std::vector<record::TopicSpec> select_link_topics(const std::vector<std::string>& include, const std::vector<std::string>& exclude) {
  std::string names;
  for (const auto& spec : link_topics()) names += (names.empty() ? "" : ", ") + spec.topic;
  for (const auto& pattern : include) {
    bool any = false;
    for (const auto& spec : link_topics()) any = any || record::matches_any(spec.topic, {pattern});
    if (!any) throw InputError("--topics '" + pattern + "' matches no link topic (known with --downlink: " + names + ")");
  }
  std::vector<record::TopicSpec> chosen;
  for (const auto& spec : link_topics()) {
    if (record::is_selected(spec.topic, include, exclude)) chosen.push_back(spec);
  }
  if (chosen.empty()) throw InputError("--topics/--exclude leave no topic to serve");
  return chosen;
}

template <class Fn>
decltype(auto) with_bridge_type(const std::string& topic, Fn&& fn) {
  if (topic == dds::kDownlinkResultsTopic) return fn.template operator()<msg::FrameResultsPubSubType>();
  if (topic == dds::kDownlinkPreviewTopic) return fn.template operator()<msg::FramePubSubType>();
  return record::with_topic_type(topic, std::forward<Fn>(fn));
}

int foxglove_main(int argc, char** argv) {
  dds::NodeOptions node;
  node.heap_reserve_mb = 0;
  foxglove::WsServerOptions server_options;
  std::vector<std::string> topics, exclude;
  std::string image_format = "jpeg", cpu_priority = "idle";
  record::FoxgloveOptions options;
  uint64_t client_buffer_mb = 32;
  double duration_s = 0.0, image_fps = 10.0;
  bool downlink = false;
  return run_app(argc, argv, "foxglove", "live bridge to Foxglove (WebSocket protocol) for the chain's topics", [&](CLI::App& app) {
    app.add_option("--address", server_options.address, "address to listen on (0.0.0.0: every interface)")->capture_default_str();
    app.add_option("--port", server_options.port, "TCP port (0: any free port, printed)")
        ->check(CLI::Range(0, 65535))
        ->capture_default_str();
    app.add_option("--topics", topics, "uavmot topics or wildcard patterns to serve (default: every uavmot topic)");
    app.add_option("--exclude", exclude, "topics or wildcard patterns not to serve");
    app.add_flag("--downlink", downlink,
                 "serve the air -> ground link's topics (uavmot/downlink/results, uavmot/downlink/preview, health) "
                 "instead of the chain's: the ground station of a split deployment");
    app.add_option("--image-format", image_format, "uavmot/foxglove/image as jpeg (CompressedImage) or raw (RawImage)")
        ->check(CLI::IsMember({"jpeg", "raw"}))
        ->capture_default_str();
    app.add_option("--jpeg-quality", options.jpeg_quality, "JPEG quality of the image channel")
        ->check(CLI::Range(1, 100))
        ->capture_default_str();
    app.add_option("--image-fps", image_fps,
                   "most images a second on uavmot/foxglove/image, evenly spaced (encoding costs the chain CPU); 0: every frame")
        ->check(uavmot::non_negative_finite())
        ->capture_default_str();
    app.add_option("--gsd", options.style.gsd_m, "ground sampling distance, m/px (> 0: track labels in km/h)")
        ->check(uavmot::non_negative_finite());
    app.add_option("--fps", options.style.fps, "frame rate, for km/h")->check(uavmot::positive_finite())->capture_default_str();
    app.add_option("--client-buffer-mb", client_buffer_mb, "MiB queued per viewer before its messages are dropped")
        ->check(uavmot::positive_finite())
        ->capture_default_str();
    app.add_option("--duration", duration_s, "stop after this many seconds (default: until Ctrl-C / SIGTERM)")
        ->check(uavmot::non_negative_finite());
    app.add_option("--cpu-priority", cpu_priority,
                   "idle: the bridge runs only on CPU time the chain leaves (SCHED_IDLE; viewers lose images "
                   "when the cores are busy, the chain loses nothing); normal: shares the cores evenly with the chain")
        ->check(CLI::IsMember({"idle", "normal"}))
        ->capture_default_str();
    dds::add_node_options(app, node);
    return [&]() -> int {
      // First, so every thread the DDS participant and the WebSocket server start inherits it. A
      // sandbox that forbids the call (a seccomp profile) costs the chain CPU, not the viewers their data.
      try {
        set_cpu_priority(parse_cpu_priority(cpu_priority));
      } catch (const InputError& e) {
        spdlog::warn("foxglove: {}; running at the scheduler's default priority", e.what());
      }
      dds::finalize(node, "foxglove");
      options.image_format = foxglove::parse_image_format(image_format);
      server_options.client_buffer_bytes = client_buffer_mb << 20;
      // Slightly under the period, so frames arriving at exactly the rate are not skipped by jitter.
      const uint64_t image_interval_ns = image_fps > 0 ? static_cast<uint64_t>(0.9e9 / image_fps) : 0;
      const auto chosen = downlink ? select_link_topics(topics, exclude) : record::select_topics(topics, exclude);
      const std::string idl_dir = record::find_idl_dir();
      install_shutdown_handler();
      foxglove::WsServer server(server_options);  // listening, or a clear InputError
      dds::Participant participant(node.dds);
      std::unique_ptr<WriterStarts> starts;
      if (node.dds.mode == dds::DeliveryMode::Lossless) starts = std::make_unique<WriterStarts>(participant);
      std::vector<std::unique_ptr<TopicBridge>> bridges;
      for (const auto& spec : chosen) {
        bridges.push_back(with_bridge_type(spec.topic, [&]<class P>() -> std::unique_ptr<TopicBridge> {
          return std::make_unique<TypedBridge<P>>(participant, spec, idl_dir, options, server, starts.get(), image_interval_ns);
        }));
      }
      spdlog::info("foxglove: serving {} {} topics on ws://{}:{} (Foxglove: Open connection -> Foxglove WebSocket), CPU priority {}",
                   chosen.size(), downlink ? "link" : "uavmot", server_options.address, server.port(), to_string(current_cpu_priority()));
      const auto start = std::chrono::steady_clock::now();
      while (!shutdown_requested()) {
        if (starts) starts->update();
        size_t taken = 0;
        for (auto& b : bridges) taken += b->drain();
        if (duration_s > 0 && std::chrono::steady_clock::now() - start > std::chrono::duration<double>(duration_s)) break;
        if (taken == 0) {
          // Wake for the next sample of a watched topic; with nothing watched, look for new
          // subscriptions 50 times a second.
          const auto reading = std::find_if(bridges.begin(), bridges.end(), [](const auto& b) { return b->reading(); });
          if (reading != bridges.end()) {
            (*reading)->wait_for_data(std::chrono::milliseconds(2));
          } else {
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
          }
        }
      }
      const auto c = server.counts();
      uint64_t invalid = 0;
      for (const auto& b : bridges) invalid += b->invalid();
      spdlog::info("foxglove: {} viewers served, {} messages sent, {} dropped for slow viewers, {} invalid samples",
                   c.clients_seen, c.messages_sent, c.messages_dropped, invalid);
      return kExitOk;
    };
  });
}

}  // namespace
}  // namespace uavmot

int main(int argc, char** argv) { return uavmot::foxglove_main(argc, argv); }
