// uavmot-motion: frames in (uavmot/frames), motion estimates out (uavmot/motion).
// One MotionEstimator per stream; in live mode the newest frame wins and gaps count as drops.

#include <algorithm>
#include <map>

#include "framePubSubTypes.h"
#include "motionPubSubTypes.h"
#include "uavmot/config/chain_config.hpp"
#include "uavmot/core/app.hpp"
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

int motion_main(int argc, char** argv) {
  dds::NodeOptions node;
  config::NodeConfigArgs config_args;
  int streams = 1;
  std::string features = "all";
  return run_app(argc, argv, "motion", "estimate camera motion and independently moving features (frames -> motion)", [&](CLI::App& app) {
    config::add_node_config_options(app, config_args, "scene and motion");
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
      const auto config = config::load_node_config(config_args);
      const auto options = config.layer("motion", motion::load_motion_options);

      dds::Participant participant(node.dds);
      std::map<std::string, motion::MotionEstimator> estimators;
      using Node = dds::SingleInputNode<msg::FramePubSubType, msg::MotionEstimatePubSubType, Frame>;
      Node single(participant,
                  {"motion", dds::kFramesTopic, dds::kMotionTopic, dds::TopicClass::Frames, streams, node.wait_subscribers},
                  [&](const std::string& stream, const Frame& frame) {
                    auto& estimator = estimators.try_emplace(stream, options, config.scene).first->second;
                    auto out = dds::to_msg(estimator.process(frame));
                    if (moving_only) keep_moving_features(out);
                    return std::optional(std::move(out));
                  });
      return single.run();
    };
  });
}

}  // namespace
}  // namespace uavmot

int main(int argc, char** argv) { return uavmot::motion_main(argc, argv); }
