// uavmot-tracking: motion estimates + segmentation in, tracks out (uavmot/tracks).
// With --state-dir, the tracker's state is saved after every frame and published on
// uavmot/tracker_state; a restarted instance restores it and continues with the same track ids.

#include <filesystem>
#include <map>

#include <spdlog/spdlog.h>

#include "motionPubSubTypes.h"
#include "segmentationPubSubTypes.h"
#include "tracker_statePubSubTypes.h"
#include "tracker_state_io.hpp"
#include "tracksPubSubTypes.h"
#include "uavmot/config/chain_config.hpp"
#include "uavmot/core/app.hpp"
#include "uavmot/core/error.hpp"
#include "uavmot/dds/node_options.hpp"
#include "uavmot/dds/paired_node.hpp"
#include "uavmot/tracking/tracker.hpp"
#include "uavmot/tracking/tracker_options.hpp"

namespace uavmot {
namespace {

struct StreamTracker {
  tracking::Tracker tracker;
  int64_t restored_frame = 0;  // inputs up to this frame are already in the restored state
  int64_t saved_frame = 0;     // the last frame whose state is in the state file
};

int tracking_main(int argc, char** argv) {
  dds::NodeOptions node;
  double upstream_timeout_s = 0.0;
  config::NodeConfigArgs config_args;
  std::string state_dir;
  int streams = 1;
  return run_app(argc, argv, "tracking", "track moving objects (motion + segmentation -> tracks)", [&](CLI::App& app) {
    config::add_node_config_options(app, config_args, "scene and tracking");
    app.add_option("--streams", streams, "exit after this many streams ended")->check(uavmot::positive_finite())->capture_default_str();
    app.add_option("--state-dir", state_dir, "save the tracker state here after every frame and restore it on start");
    dds::add_upstream_timeout_option(app, upstream_timeout_s);
    dds::add_node_options(app, node);
    return [&]() -> int {
      dds::finalize(node, "tracking");
      install_shutdown_handler();
      const auto config = config::load_node_config(config_args);
      const auto options = config.layer("tracking", tracking::load_tracker_options);
      if (!state_dir.empty()) std::filesystem::create_directories(state_dir);
      dds::Participant participant(node.dds);
      auto state_out = participant.make_writer<msg::TrackerSnapshotPubSubType>(dds::kTrackerStateTopic, dds::TopicClass::State);
      std::map<std::string, StreamTracker> trackers;
      auto state_file = [&](const std::string& stream) { return state_dir + "/tracker_state_" + stream + ".cdr"; };

      auto tracker_for = [&](const std::string& stream) -> StreamTracker& {
        auto [it, fresh] = trackers.try_emplace(stream, StreamTracker{tracking::Tracker(options, config.scene), 0, 0});
        if (fresh && !state_dir.empty()) {
          if (auto snapshot = tracking::load_snapshot(state_file(stream))) {
            std::string why;
            auto state = tracking::from_msg(*snapshot, why);
            if (!state) throw InputError("tracker state '" + state_file(stream) + "': " + why);
            it->second.tracker.restore(*state);
            it->second.restored_frame = snapshot->frame_index();
            spdlog::info("stream '{}': restored {} tracks at frame {} (next id {})", stream, state->tracks.size(),
                         snapshot->frame_index(), state->next_id);
          }
        }
        return it->second;
      };

      using Node = dds::PairedNode<msg::MotionEstimatePubSubType, msg::SegmentationPubSubType, msg::TrackListPubSubType,
                                   MotionEstimate, SegmentationResult>;
      // With saved state, also take what the upstream writers published while this process was down.
      const auto inputs = state_dir.empty() ? dds::TopicClass::Chain : dds::TopicClass::ChainResume;
      Node paired(participant,
                  {"tracking", dds::kMotionTopic, dds::kSegmentationTopic, dds::kTracksTopic, inputs, inputs, streams,
                   node.wait_subscribers, upstream_timeout_s},
                  [&](const std::string& stream, int64_t index, const MotionEstimate& motion,
                      const SegmentationResult& segmentation) -> std::optional<msg::TrackList> {
                    StreamTracker& s = tracker_for(stream);
                    if (index <= s.restored_frame) return std::nullopt;  // already in the restored state
                    return dds::to_msg(s.tracker.process(motion, segmentation));
                  },
                  // The state is saved once the frame's tracks are out: a crash in between makes the
                  // respawned tracker redo that frame, and the sink skips the repeat.
                  [&](const std::string& stream, int64_t index) {
                    if (state_dir.empty()) return;
                    auto snapshot = tracking::to_msg(trackers.at(stream).tracker.state(), stream, index);
                    try {
                      tracking::save_snapshot(snapshot, state_file(stream));
                      trackers.at(stream).saved_frame = index;
                    } catch (const OutputError& e) {
                      spdlog::warn("cannot write tracker state: {}", e.what());
                    }
                    state_out->write(snapshot);
                  });
      const int code = paired.run();
      // Where a later run picks up (docs/launch.md: a new launch continues from the saved state).
      for (const auto& [stream, s] : trackers) {
        if (s.saved_frame > 0) spdlog::info("stream '{}': state saved at frame {} in '{}'", stream, s.saved_frame, state_file(stream));
      }
      return code;
    };
  });
}

}  // namespace
}  // namespace uavmot

int main(int argc, char** argv) { return uavmot::tracking_main(argc, argv); }
