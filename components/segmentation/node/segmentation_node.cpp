// uavmot-segmentation: frames + motion estimates in, clusters + regions out (uavmot/segmentation).
// With --state-dir, each segmenter's state (the shift check's previous windows) is saved after every
// frame, the last --state-keep kept (uavmot/core/state_ring.hpp); a new launch that starts after
// frame K restores the state of K and segments K+1 as an uninterrupted run did.

#include <chrono>
#include <filesystem>
#include <map>
#include <optional>

#include <spdlog/spdlog.h>

#include "framePubSubTypes.h"
#include "motionPubSubTypes.h"
#include "segmentationPubSubTypes.h"
#include "uavmot/config/chain_config.hpp"
#include "uavmot/core/app.hpp"
#include "uavmot/core/error.hpp"
#include "uavmot/core/state_ring.hpp"
#include "uavmot/dds/node_options.hpp"
#include "uavmot/dds/paired_node.hpp"
#include "uavmot/segmentation/segmentation_options.hpp"
#include "uavmot/segmentation/segmenter.hpp"

namespace uavmot {
namespace {

struct StreamSegmentation {
  segmentation::Segmenter segmenter;
  std::optional<StateRing> states{};  // with --state-dir
  int64_t saved_frame = 0;
  uint64_t saves = 0;
  double save_ms = 0.0;  // total time of save_state() and the ring's save (synced write, removals)
};

int segmentation_main(int argc, char** argv) {
  dds::NodeOptions node;
  double upstream_timeout_s = 0.0;
  config::NodeConfigArgs config_args;
  std::string method;
  int streams = 1;
  bool resume = false;
  std::string state_dir;
  int state_keep = kDefaultStatesKept;
  return run_app(argc, argv, "segmentation", "segment moving objects (frames + motion -> clusters and regions)", [&](CLI::App& app) {
    config::add_node_config_options(app, config_args, "scene and segmentation");
    app.add_option("--segmentation", method, segmentation_method_choices())->check(CLI::IsMember(segmentation_method_names()));
    app.add_option("--streams", streams, "exit after this many streams ended")->check(uavmot::positive_finite())->capture_default_str();
    app.add_flag("--resume", resume,
                 "after a crash (lossless): also read the writers' recent history, so the frame that reached the killed "
                 "process but not its output comes again (the frames already segmented come again too: readers skip them)");
    app.add_option("--state-dir", state_dir,
                   "save each stream's segmentation state (the previous frame's cluster windows) here after every "
                   "frame and restore the one before the first frame received on start");
    app.add_option("--state-keep", state_keep, "saved states kept per stream (the newest N)")
        ->check(states_kept_check("segmentation"))
        ->capture_default_str();
    dds::add_upstream_timeout_option(app, upstream_timeout_s);
    dds::add_node_options(app, node);
    return [&]() -> int {
      dds::finalize(node, "segmentation");
      install_shutdown_handler();
      const auto config = config::load_node_config(config_args);
      auto options = config.layer("segmentation", segmentation::load_segmentation_options);
      if (!method.empty()) options.method = parse_segmentation_method(method);
      if (!state_dir.empty()) std::filesystem::create_directories(state_dir);
      dds::Participant participant(node.dds);
      std::map<std::string, StreamSegmentation> streams_seen;
      using Node = dds::PairedNode<msg::FramePubSubType, msg::MotionEstimatePubSubType, msg::SegmentationPubSubType, Frame, MotionEstimate>;
      Node paired(participant,
                  {"segmentation", dds::kFramesTopic, dds::kMotionTopic, dds::kSegmentationTopic,
                   resume ? dds::TopicClass::FramesResume : dds::TopicClass::Frames,
                   resume ? dds::TopicClass::ChainResume : dds::TopicClass::Chain, streams, node.wait_subscribers,
                   upstream_timeout_s},
                  [&](const std::string& stream, int64_t index, const Frame& frame, const MotionEstimate& motion) {
                    auto [it, fresh] = streams_seen.try_emplace(stream, StreamSegmentation{segmentation::Segmenter(options, config.scene)});
                    if (fresh && !state_dir.empty()) {
                      it->second.states.emplace(state_dir, "segmentation_state", stream, state_keep);
                      // The state of index - 1 continues exactly; an older one leaves the shift check out
                      // for the first frame, as no state does.
                      restore_and_report(*it->second.states, stream, index, [&](const std::vector<uint8_t>& bytes) {
                        it->second.segmenter.restore_state(bytes);
                        return it->second.segmenter.last_frame_index();
                      });
                    }
                    return std::optional(dds::to_msg(it->second.segmenter.process(frame, motion)));
                  },
                  // Saved once the frame's regions are out: a crash in between redoes the frame.
                  [&](const std::string& stream, int64_t index) {
                    StreamSegmentation& s = streams_seen.at(stream);
                    if (!s.states) return;
                    const auto t0 = std::chrono::steady_clock::now();
                    try {
                      s.states->save(index, s.segmenter.save_state());
                    } catch (const OutputError& e) {
                      spdlog::warn("cannot write segmentation state: {}", e.what());
                      return;
                    }
                    s.save_ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
                    ++s.saves;
                    s.saved_frame = index;
                  });
      const int code = paired.run();
      for (const auto& [stream, s] : streams_seen) {
        if (s.saves > 0) {
          spdlog::info("stream '{}': segmentation state saved at frame {} in '{}' ({} saves, on average {:.2f} ms to "
                       "serialise, write, sync and remove the oldest; {} kept)",
                       stream, s.saved_frame, s.states->path(s.saved_frame), s.saves, s.save_ms / static_cast<double>(s.saves),
                       s.states->frames().size());
        }
      }
      return code;
    };
  });
}

}  // namespace
}  // namespace uavmot

int main(int argc, char** argv) { return uavmot::segmentation_main(argc, argv); }
