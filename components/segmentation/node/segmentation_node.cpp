// uavmot-segmentation: frames + motion estimates in, clusters + regions out (uavmot/segmentation).

#include <map>

#include "framePubSubTypes.h"
#include "motionPubSubTypes.h"
#include "segmentationPubSubTypes.h"
#include "uavmot/config/chain_config.hpp"
#include "uavmot/core/app.hpp"
#include "uavmot/dds/node_options.hpp"
#include "uavmot/dds/paired_node.hpp"
#include "uavmot/segmentation/segmentation_options.hpp"
#include "uavmot/segmentation/segmenter.hpp"

namespace uavmot {
namespace {

int segmentation_main(int argc, char** argv) {
  dds::NodeOptions node;
  double upstream_timeout_s = 0.0;
  config::NodeConfigArgs config_args;
  std::string method;
  int streams = 1;
  bool resume = false;
  return run_app(argc, argv, "segmentation", "segment moving objects (frames + motion -> clusters and regions)", [&](CLI::App& app) {
    config::add_node_config_options(app, config_args, "scene and segmentation");
    app.add_option("--segmentation", method, segmentation_method_choices())->check(CLI::IsMember(segmentation_method_names()));
    app.add_option("--streams", streams, "exit after this many streams ended")->check(uavmot::positive_finite())->capture_default_str();
    app.add_flag("--resume", resume,
                 "after a crash (lossless): also read the writers' recent history, so the frame that reached the killed "
                 "process but not its output comes again (the frames already segmented come again too: readers skip them)");
    dds::add_upstream_timeout_option(app, upstream_timeout_s);
    dds::add_node_options(app, node);
    return [&]() -> int {
      dds::finalize(node, "segmentation");
      install_shutdown_handler();
      const auto config = config::load_node_config(config_args);
      auto options = config.layer("segmentation", segmentation::load_segmentation_options);
      if (!method.empty()) options.method = parse_segmentation_method(method);
      dds::Participant participant(node.dds);
      std::map<std::string, segmentation::Segmenter> segmenters;
      using Node = dds::PairedNode<msg::FramePubSubType, msg::MotionEstimatePubSubType, msg::SegmentationPubSubType, Frame, MotionEstimate>;
      Node paired(participant,
                  {"segmentation", dds::kFramesTopic, dds::kMotionTopic, dds::kSegmentationTopic,
                   resume ? dds::TopicClass::FramesResume : dds::TopicClass::Frames,
                   resume ? dds::TopicClass::ChainResume : dds::TopicClass::Chain, streams, node.wait_subscribers,
                   upstream_timeout_s},
                  [&](const std::string& stream, int64_t, const Frame& frame, const MotionEstimate& motion) {
                    auto& segmenter = segmenters.try_emplace(stream, options, config.scene).first->second;
                    return std::optional(dds::to_msg(segmenter.process(frame, motion)));
                  });
      return paired.run();
    };
  });
}

}  // namespace
}  // namespace uavmot

int main(int argc, char** argv) { return uavmot::segmentation_main(argc, argv); }
