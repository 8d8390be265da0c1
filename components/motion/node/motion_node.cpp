// uavmot-motion: frames in (uavmot/frames), motion estimates out (uavmot/motion).
// One MotionEstimator per stream; in live mode the newest frame wins and gaps count as drops.

#include <algorithm>
#include <map>

#include <spdlog/spdlog.h>

#include "framePubSubTypes.h"
#include "motionPubSubTypes.h"
#include "uavmot/core/app.hpp"
#include "uavmot/core/shutdown.hpp"
#include "uavmot/dds/chain_convert.hpp"
#include "uavmot/dds/frame_convert.hpp"
#include "uavmot/dds/health_reporter.hpp"
#include "uavmot/dds/node_options.hpp"
#include "uavmot/dds/node_support.hpp"
#include "uavmot/motion/motion_estimator.hpp"
#include "uavmot/pipeline/chain.hpp"

namespace uavmot {
namespace {

int motion_main(int argc, char** argv) {
  dds::NodeOptions node;
  std::string config_file;
  double gsd_m = 0.0, fps = 0.0;
  int streams = 1;
  std::string features = "all";
  return run_app(argc, argv, "motion", "estimate camera motion and independently moving features (frames -> motion)", [&](CLI::App& app) {
    app.add_option("--config", config_file, "chain configuration YAML (uses sections scene and motion)");
    app.add_option("--gsd", gsd_m, "ground sampling distance, m/px")->check(CLI::PositiveNumber);
    app.add_option("--fps", fps, "frame rate")->check(CLI::PositiveNumber);
    app.add_option("--streams", streams, "exit after this many streams ended")->check(CLI::PositiveNumber)->capture_default_str();
    app.add_option("--features", features,
                   "features to publish: all, or only the moving ones (all that segmentation and tracking use; "
                   "about 7x fewer bytes on a downlink)")
        ->check(CLI::IsMember({"all", "moving"}))
        ->capture_default_str();
    dds::add_node_options(app, node);
    return [&]() -> int {
      dds::finalize(node, "motion");
      const bool moving_only = features == "moving";
      install_shutdown_handler();
      auto options = config_file.empty() ? pipeline::ChainOptions{} : pipeline::load_chain_options(config_file);
      if (gsd_m > 0) options.scene.gsd_m = gsd_m;
      if (fps > 0) options.scene.fps = fps;

      dds::Participant participant(node.dds);
      auto frames = participant.make_reader<msg::FramePubSubType>(dds::kFramesTopic, dds::TopicClass::Frames);
      auto motion_out = participant.make_writer<msg::MotionEstimatePubSubType>(dds::kMotionTopic, dds::TopicClass::Chain);
      if (node.dds.mode == dds::DeliveryMode::Lossless) motion_out->set_required_readers(node.wait_subscribers);
      dds::HealthReporter health(participant, "motion", "*");
      health.watch(*frames);
      health.watch(*motion_out);
      spdlog::info("{} -> {} ({}, waiting for {} reader(s))", dds::kFramesTopic, dds::kMotionTopic, node.mode,
                   node.wait_subscribers);
      std::map<std::string, motion::MotionEstimator> estimators;
      std::map<std::string, int64_t> last_index;
      dds::StreamEnds ends(streams);
      dds::RejectLog rejects;
      msg::Frame sample;
      while (!shutdown_requested() && !ends.all_ended()) {
        health.set_queue_depth(static_cast<uint32_t>(frames->unread()));
        health.tick();
        if (!frames->wait_for_data(std::chrono::milliseconds(200))) continue;
        while (frames->take(sample)) {
          const std::string stream = sample.stream_id().to_string();
          if (sample.end_of_stream()) {
            msg::MotionEstimate eos;
            eos.stream_id(stream);
            eos.frame_index(sample.frame_index());
            eos.end_of_stream(true);
            motion_out->write_reliably(eos, dds::end_of_stream_patience(node.dds.mode));
            ends.end(stream);
            continue;
          }
          health.frame_in();
          std::string why;
          auto frame = dds::view_msg(sample, why);  // processed before the next take: no copy
          if (!frame) {
            health.invalid_sample();
            rejects.log(dds::kFramesTopic, why);
            continue;
          }
          if (auto it = last_index.find(stream); it != last_index.end() && frame->index <= it->second) {
            continue;  // a respawned source sends its last frame again (it cannot know it arrived): seen already
          } else if (it != last_index.end() && frame->index > it->second + 1) {
            health.dropped(static_cast<uint64_t>(frame->index - it->second - 1));
          }
          last_index[stream] = frame->index;
          const auto t0 = std::chrono::steady_clock::now();
          auto& estimator = estimators.try_emplace(stream, options.motion, options.scene).first->second;
          auto out = dds::to_msg(estimator.process(*frame));
          if (moving_only) {
            auto& f = out.features();
            f.erase(std::remove_if(f.begin(), f.end(), [](const msg::Feature& x) { return !x.moving(); }), f.end());
          }
          const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
          if (!dds::publish(*motion_out, out, node.dds.mode)) health.dropped();
          health.frame_out(frame->index, ms, dds::latency_ms_since(frame->capture_time_ns));
          health.set_bytes_out(motion_out->bytes_sent());
        }
      }
      motion_out->flush(dds::end_of_stream_patience(node.dds.mode));
      health.report(msg::ComponentState::FINISHED);
      return kExitOk;
    };
  });
}

}  // namespace
}  // namespace uavmot

int main(int argc, char** argv) { return uavmot::motion_main(argc, argv); }
