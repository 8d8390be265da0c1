// uavmot-test-inject: a participant that tries to inject made-up results into a ground station
// (uavmot/downlink/results) for a stream: one bogus track (id 424242) per frame index 1..N, over
// and over, for --seconds. Prints whether its writer was refused and how many readers it matched.
// Exit 0 after writing, 3 when the writer could not even be created (refused by access control).

#include <algorithm>
#include <memory>
#include <thread>

#include <spdlog/spdlog.h>

#include "downlinkPubSubTypes.h"
#include "uavmot/core/app.hpp"
#include "uavmot/core/error.hpp"
#include "uavmot/core/shutdown.hpp"
#include "uavmot/dds/node_options.hpp"

namespace uavmot {
namespace {

int inject_main(int argc, char** argv) {
  dds::NodeOptions node;
  std::string stream = "uav1";
  double seconds = 10.0;
  int frames = 100;
  return run_app(argc, argv, "test-inject", "try to inject bogus tracks into uavmot/downlink/results (tests)", [&](CLI::App& app) {
    app.add_option("--stream", stream, "stream id to impersonate")->capture_default_str();
    app.add_option("--seconds", seconds, "how long to keep writing")->capture_default_str();
    app.add_option("--frames", frames, "frame indices 1..N, repeated")->capture_default_str();
    node.dds.participant_profile = "udp";
    dds::add_node_options(app, node);
    return [&]() -> int {
      dds::finalize(node, "inject");
      install_shutdown_handler();
      dds::Participant participant(node.dds);
      std::unique_ptr<dds::TopicWriter<msg::FrameResultsPubSubType>> writer;
      try {
        writer = participant.make_writer<msg::FrameResultsPubSubType>(dds::kDownlinkResultsTopic, dds::TopicClass::Downlink);
      } catch (const InputError& e) {
        spdlog::info("writer refused: {}", e.what());
        return 3;
      }
      const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
      int max_matched = 0;
      uint64_t written = 0;
      for (int k = 1; std::chrono::steady_clock::now() < end && !shutdown_requested(); k = k % frames + 1) {
        msg::FrameResults sample;
        sample.stream_id(stream);
        sample.frame_index(k);
        sample.has_tracks(true);
        msg::CompactTrack track;
        track.id(424242);
        track.state(msg::TrackState::CONFIRMED);
        track.box().cx(10.0F);
        track.box().cy(10.0F);
        track.box().width(2.0F);
        track.box().length(5.0F);
        sample.tracks().push_back(track);
        if (writer->write(sample)) ++written;
        max_matched = std::max(max_matched, writer->matched());
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
      }
      spdlog::info("wrote {} samples; matched at most {} reader(s)", written, max_matched);
      return 0;
    };
  });
}

}  // namespace
}  // namespace uavmot

int main(int argc, char** argv) { return uavmot::inject_main(argc, argv); }
