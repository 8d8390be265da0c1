// uavmot-downlink: the UAV's gateway to the ground (uavmot/downlink/downlink.hpp): the chain's
// results, the air components' health and optional JPEG previews, relayed from the UAV's own
// domain onto the radio link. This file only reads the command line.

#include "uavmot/core/app.hpp"
#include "uavmot/core/shutdown.hpp"
#include "uavmot/dds/node_options.hpp"
#include "uavmot/downlink/downlink.hpp"

namespace uavmot {
namespace {

int downlink_main(int argc, char** argv) {
  downlink::DownlinkOptions o;
  auto& preview = o.preview;
  return run_app(argc, argv, "downlink", "relay the chain's results to the ground in compact form (air -> link)", [&](CLI::App& app) {
    app.add_option("--air-domain", o.air_domain, "DDS domain of the UAV's own processes")->check(CLI::Range(0, 232))->capture_default_str();
    app.add_option("--air-transport", o.air_transport, "participant profile on the UAV's side (shm: never on the link)")
        ->capture_default_str();
    app.add_option("--stream-id", o.stream_id, "this UAV's stream: the only one relayed (others are filtered out), and health reports of nodes "
                   "serving every stream (\"*\") get it; \"*\": relay every stream")
        ->capture_default_str();
    app.add_option("--streams", o.streams, "exit after this many streams ended")->check(uavmot::positive_finite())->capture_default_str();
    app.add_flag("--resume", o.resume,
                 "a respawn: also take the air chain writers' recent history (the last 64 samples of each), so "
                 "what reached the killed downlink but not the ground is sent again (the ground sink skips repeats)");
    dds::add_upstream_timeout_option(app, o.upstream_timeout_s);
    app.add_option("--preview-rate", preview.rate_hz, "JPEG previews of the frames per second (0: none)")
        ->check(uavmot::non_negative_finite())->capture_default_str();
    app.add_option("--preview-width", preview.width, "preview width, px (height keeps the aspect ratio)")
        ->check(CLI::Range(16, 8192))->capture_default_str();
    app.add_option("--preview-quality", preview.quality, "preview JPEG quality")->check(CLI::Range(1, 100))->capture_default_str();
    app.add_option("--preview-kbps", preview.kbps, "the preview's share of the link, kbit/s (a flow controller; 0: unlimited)")
        ->check(uavmot::non_negative_finite())->capture_default_str();
    o.link.dds.participant_profile = "udp";
    dds::add_node_options(app, o.link);
    return [&]() -> int {
      dds::finalize(o.link, "downlink");
      install_shutdown_handler();
      return downlink::run_downlink(o);
    };
  });
}

}  // namespace
}  // namespace uavmot

int main(int argc, char** argv) { return uavmot::downlink_main(argc, argv); }
