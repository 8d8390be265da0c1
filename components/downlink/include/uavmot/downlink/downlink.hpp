#pragma once
// uavmot-downlink's process: the UAV's one process on the radio link. It reads motion,
// segmentation and tracks on the UAV's own domain (shared memory, never on the link) and
// publishes on the link's domain, once per frame, what the ground uses:
//   uavmot/motion + uavmot/segmentation + uavmot/tracks -> uavmot/downlink/results (ResultsRelay)
//   uavmot/health -> uavmot/health      the air components' reports, stream "*" -> stream_id
//   uavmot/frames -> uavmot/downlink/preview   optional JPEG previews (PreviewRelay)
// It exits when every stream ended.

#include <string>

#include "uavmot/dds/node_options.hpp"
#include "uavmot/downlink/preview_relay.hpp"

namespace uavmot::downlink {

struct DownlinkOptions {
  dds::NodeOptions link;  // --domain, --transport (udp), --mode, --wait-subscribers (ground readers); finalized
  int air_domain = 1;
  std::string air_transport = "shm";  // never on the link
  std::string stream_id = "*";        // given to health reports of nodes serving every stream
  int streams = 1;
  // A respawned downlink: its readers also get the chain writers' recent history (transient-local,
  // the last 64 samples each), so what reached its killed predecessor but not the link comes again
  // (the ground sink skips the frames it has).
  bool resume = false;
  double upstream_timeout_s = 0.0;  // give up when the air chain's writers are gone this long (0: never)
  PreviewOptions preview;
};

// Runs until every stream ended or a shutdown was requested; returns the exit code. Throws
// InputError for options that cannot work (both sides on the same domain and transport).
int run_downlink(DownlinkOptions options);

}  // namespace uavmot::downlink
