// uavmot-tracking: motion estimates + segmentation in, tracks out (uavmot/tracks).

#include <map>

#include "motionPubSubTypes.h"
#include "segmentationPubSubTypes.h"
#include "tracksPubSubTypes.h"
#include "uavmot/core/app.hpp"
#include "uavmot/dds/node_options.hpp"
#include "uavmot/dds/paired_node.hpp"
#include "uavmot/pipeline/chain.hpp"
#include "uavmot/tracking/tracker.hpp"

namespace uavmot {
namespace {

int tracking_main(int argc, char** argv) {
  dds::NodeOptions node;
  std::string config_file;
  double gsd_m = 0.0, fps = 0.0;
  int streams = 1;
  return run_app(argc, argv, "tracking", "track moving objects (motion + segmentation -> tracks)", [&](CLI::App& app) {
    app.add_option("--config", config_file, "chain configuration YAML (uses sections scene and tracking)");
    app.add_option("--gsd", gsd_m, "ground sampling distance, m/px")->check(CLI::PositiveNumber);
    app.add_option("--fps", fps, "frame rate")->check(CLI::PositiveNumber);
    app.add_option("--streams", streams, "exit after this many streams ended")->check(CLI::PositiveNumber)->capture_default_str();
    dds::add_node_options(app, node);
    return [&]() -> int {
      dds::finalize(node, "tracking");
      install_shutdown_handler();
      auto options = config_file.empty() ? pipeline::ChainOptions{} : pipeline::load_chain_options(config_file);
      if (gsd_m > 0) options.scene.gsd_m = gsd_m;
      if (fps > 0) options.scene.fps = fps;
      dds::Participant participant(node.dds);
      std::map<std::string, tracking::Tracker> trackers;
      using Node = dds::PairedNode<msg::MotionEstimatePubSubType, msg::SegmentationPubSubType, msg::TrackListPubSubType,
                                   MotionEstimate, SegmentationResult>;
      Node paired(participant,
                  {"tracking", dds::kMotionTopic, dds::kSegmentationTopic, dds::kTracksTopic, dds::TopicClass::Chain,
                   dds::TopicClass::Chain, streams, node.wait_subscribers},
                  [&](const std::string& stream, const MotionEstimate& motion, const SegmentationResult& segmentation) {
                    auto& tracker = trackers.try_emplace(stream, options.tracking, options.scene).first->second;
                    tracker.set_image_size(motion.image_width, motion.image_height);
                    return dds::to_msg(tracker.process(motion, segmentation));
                  });
      return paired.run();
    };
  });
}

}  // namespace
}  // namespace uavmot

int main(int argc, char** argv) { return uavmot::tracking_main(argc, argv); }
