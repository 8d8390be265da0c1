// uavmot-segmentation: frames + motion estimates in, clusters + regions out (uavmot/segmentation).

#include <map>

#include "framePubSubTypes.h"
#include "motionPubSubTypes.h"
#include "segmentationPubSubTypes.h"
#include "uavmot/core/app.hpp"
#include "uavmot/dds/node_options.hpp"
#include "uavmot/dds/paired_node.hpp"
#include "uavmot/pipeline/chain.hpp"
#include "uavmot/segmentation/segmenter.hpp"

namespace uavmot {
namespace {

int segmentation_main(int argc, char** argv) {
  dds::NodeOptions node;
  std::string config_file, method;
  double gsd_m = 0.0, fps = 0.0;
  int streams = 1;
  bool resume = false;
  return run_app(argc, argv, "segmentation", "segment moving objects (frames + motion -> clusters and regions)", [&](CLI::App& app) {
    app.add_option("--config", config_file, "chain configuration YAML (uses sections scene and segmentation)");
    app.add_option("--segmentation", method, "clustering, korn, morphological, lbp or fusion")
        ->check(CLI::IsMember({"clustering", "korn", "morphological", "lbp", "fusion"}));
    app.add_option("--gsd", gsd_m, "ground sampling distance, m/px")->check(CLI::PositiveNumber);
    app.add_option("--fps", fps, "frame rate")->check(CLI::PositiveNumber);
    app.add_option("--streams", streams, "exit after this many streams ended")->check(CLI::PositiveNumber)->capture_default_str();
    app.add_flag("--resume", resume,
                 "after a crash (lossless): also read the writers' recent history, so the frame that reached the killed "
                 "process but not its output comes again (the frames already segmented come again too: readers skip them)");
    dds::add_node_options(app, node);
    return [&]() -> int {
      dds::finalize(node, "segmentation");
      install_shutdown_handler();
      auto options = config_file.empty() ? pipeline::ChainOptions{} : pipeline::load_chain_options(config_file);
      if (!method.empty()) options.segmentation.method = parse_segmentation_method(method);
      if (gsd_m > 0) options.scene.gsd_m = gsd_m;
      if (fps > 0) options.scene.fps = fps;
      dds::Participant participant(node.dds);
      std::map<std::string, segmentation::Segmenter> segmenters;
      using Node = dds::PairedNode<msg::FramePubSubType, msg::MotionEstimatePubSubType, msg::SegmentationPubSubType, Frame, MotionEstimate>;
      Node paired(participant,
                  {"segmentation", dds::kFramesTopic, dds::kMotionTopic, dds::kSegmentationTopic,
                   resume ? dds::TopicClass::FramesResume : dds::TopicClass::Frames,
                   resume ? dds::TopicClass::ChainResume : dds::TopicClass::Chain, streams, node.wait_subscribers},
                  [&](const std::string& stream, int64_t, const Frame& frame, const MotionEstimate& motion) {
                    auto& segmenter = segmenters.try_emplace(stream, options.segmentation, options.scene).first->second;
                    return std::optional(dds::to_msg(segmenter.process(frame, motion)));
                  });
      return paired.run();
    };
  });
}

}  // namespace
}  // namespace uavmot

int main(int argc, char** argv) { return uavmot::segmentation_main(argc, argv); }
