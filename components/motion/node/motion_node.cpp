// uavmot-motion: frames in (uavmot/frames), motion estimates out (uavmot/motion).
// One MotionEstimator per stream; in live mode the newest frame wins and gaps count as drops.
// With --state-dir, each estimator's state is saved after every frame; a restarted instance restores
// it and continues from the next frame with the same estimates as an uninterrupted run.

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <map>

#include <spdlog/spdlog.h>

#include "framePubSubTypes.h"
#include "motionPubSubTypes.h"
#include "motion_state_file.hpp"
#include "uavmot/config/chain_config.hpp"
#include "uavmot/core/app.hpp"
#include "uavmot/core/durable_file.hpp"
#include "uavmot/core/error.hpp"
#include "uavmot/dds/node_options.hpp"
#include "uavmot/dds/single_input_node.hpp"
#include "uavmot/motion/motion_estimator.hpp"
#include "uavmot/motion/motion_options.hpp"

namespace uavmot {
namespace {

// Segmentation and tracking use only the moving features; the rest is most of a sample's bytes.
void keep_moving_features(msg::MotionEstimate& m) {
  auto& f = m.features();
  f.erase(std::remove_if(f.begin(), f.end(), [](const msg::Feature& x) { return !x.moving(); }), f.end());
}

struct StreamMotion {
  motion::MotionEstimator estimator;
  int64_t restored_frame = 0;  // frames up to this one are already in the restored state
  bool continued = false;      // a frame after the restored state was processed
  int64_t saved_frame = 0;     // the last frame whose state is in the state file
  uint64_t saves = 0;
  double serialise_ms = 0.0;   // total time of save_state()
  double write_ms = 0.0;       // total time of the synced write (write_file_durably)
  size_t state_bytes = 0;      // of the last save
};

int motion_main(int argc, char** argv) {
  dds::NodeOptions node;
  config::NodeConfigArgs config_args;
  int streams = 1;
  std::string features = "all";
  std::string state_dir;
  return run_app(argc, argv, "motion", "estimate camera motion and independently moving features (frames -> motion)", [&](CLI::App& app) {
    config::add_node_config_options(app, config_args, "scene and motion");
    app.add_option("--streams", streams, "exit after this many streams ended")->check(CLI::PositiveNumber)->capture_default_str();
    app.add_option("--features", features,
                   "features to publish: all, or only the moving ones (all that segmentation and tracking use; "
                   "about 7x fewer bytes on a downlink)")
        ->check(CLI::IsMember({"all", "moving"}))
        ->capture_default_str();
    app.add_option("--state-dir", state_dir,
                   "save each stream's estimator state here after every frame and restore it on start "
                   "(a respawned motion continues bit-identically)");
    dds::add_node_options(app, node);
    return [&]() -> int {
      dds::finalize(node, "motion");
      const bool moving_only = features == "moving";
      install_shutdown_handler();
      const auto config = config::load_node_config(config_args);
      const auto options = config.layer("motion", motion::load_motion_options);

      if (!state_dir.empty()) std::filesystem::create_directories(state_dir);
      dds::Participant participant(node.dds);
      std::map<std::string, StreamMotion> estimators;
      auto state_file = [&](const std::string& stream) { return state_dir + "/motion_state_" + stream + ".bin"; };
      auto estimator_for = [&](const std::string& stream) -> StreamMotion& {
        auto [it, fresh] = estimators.try_emplace(stream, StreamMotion{motion::MotionEstimator(options, config.scene)});
        if (fresh && !state_dir.empty()) {
          if (auto bytes = motion::load_state_file(state_file(stream))) {
            try {
              it->second.estimator.restore_state(*bytes);
            } catch (const InputError& e) {
              throw InputError("motion state file '" + state_file(stream) + "': " + e.what() +
                               " (remove it to start this stream afresh)");
            }
            it->second.restored_frame = it->second.estimator.last_frame_index();
            spdlog::info("stream '{}': restored the motion state at frame {} ({} bytes)", stream, it->second.restored_frame,
                         bytes->size());
          }
        }
        return it->second;
      };
      using Node = dds::SingleInputNode<msg::FramePubSubType, msg::MotionEstimatePubSubType, Frame>;
      // With saved state, also take the frames the source published while this process was down
      // (the writer's last 8, transient-local): the first of them the state does not hold is next.
      const auto frames_class = state_dir.empty() ? dds::TopicClass::Frames : dds::TopicClass::FramesResume;
      Node single(participant,
                  {"motion", dds::kFramesTopic, dds::kMotionTopic, frames_class, streams, node.wait_subscribers},
                  [&](const std::string& stream, const Frame& frame) -> std::optional<msg::MotionEstimate> {
                    StreamMotion& s = estimator_for(stream);
                    if (frame.index <= s.restored_frame) return std::nullopt;  // already in the restored state
                    if (!s.continued && s.restored_frame > 0 && frame.index != s.restored_frame + 1) {
                      spdlog::warn("stream '{}': the restored state is at frame {} but the next frame here is {}: "
                                   "the estimates after the gap differ from an uninterrupted run's",
                                   stream, s.restored_frame, frame.index);
                    }
                    s.continued = true;
                    auto out = dds::to_msg(s.estimator.process(frame));
                    if (moving_only) keep_moving_features(out);
                    return std::optional(std::move(out));
                  },
                  // The state is saved once the frame's estimate is out: a crash in between makes the
                  // respawned motion redo that frame (the same bytes), and its readers skip the repeat.
                  [&](const std::string& stream, int64_t index) {
                    if (state_dir.empty()) return;
                    StreamMotion& s = estimators.at(stream);
                    const auto t0 = std::chrono::steady_clock::now();
                    const std::vector<uint8_t> bytes = s.estimator.save_state();
                    const auto t1 = std::chrono::steady_clock::now();
                    try {
                      write_file_durably(state_file(stream), bytes);
                    } catch (const OutputError& e) {
                      spdlog::warn("cannot write motion state: {}", e.what());
                      return;
                    }
                    s.serialise_ms += std::chrono::duration<double, std::milli>(t1 - t0).count();
                    s.write_ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t1).count();
                    ++s.saves;
                    s.state_bytes = bytes.size();
                    s.saved_frame = index;
                  });
      const int code = single.run();
      for (const auto& [stream, s] : estimators) {
        if (s.saves > 0) {
          const double n = static_cast<double>(s.saves);
          spdlog::info("stream '{}': motion state saved at frame {} in '{}' ({} bytes; {} saves, on average {:.2f} ms to "
                       "serialise + {:.2f} ms to write and sync)",
                       stream, s.saved_frame, state_file(stream), s.state_bytes, s.saves, s.serialise_ms / n, s.write_ms / n);
        }
      }
      return code;
    };
  });
}

}  // namespace
}  // namespace uavmot

int main(int argc, char** argv) { return uavmot::motion_main(argc, argv); }
