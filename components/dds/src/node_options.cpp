#include "uavmot/dds/node_options.hpp"

#include "uavmot/core/app.hpp"
#include "uavmot/core/logging.hpp"
#include "uavmot/core/memory.hpp"

namespace uavmot::dds {

void add_node_options(CLI::App& app, NodeOptions& options) {
  auto* group = app.add_option_group("DDS");
  group->add_option("--domain", options.dds.domain_id, "DDS domain id")->check(CLI::Range(0, 232))->capture_default_str();
  group->add_option("--qos-profiles", options.dds.profiles_file, "Fast DDS XML profiles (default: " + default_profiles_file() + ")");
  group->add_option("--transport", options.dds.participant_profile,
                    "participant profile: local (shared memory + UDP on loopback: one host, closed to the LAN), shm (shared memory only) or udp (between hosts)")
      ->capture_default_str();
  group->add_option("--discovery-server", options.dds.discovery_server,
                    "IP:PORT of a Fast DDS Discovery Server (id 0) instead of multicast discovery; empty: multicast");
  group->add_option("--mode", options.mode, "lossless: nothing dropped, slow readers hold writers back; live: newest wins")
      ->check(CLI::IsMember({"lossless", "live"}))
      ->capture_default_str();
  group->add_option("--wait-subscribers", options.wait_subscribers,
                    "lossless: publish only while this many readers of the output are matched")
      ->check(uavmot::non_negative_finite())
      ->capture_default_str();
  app.add_option("--heap-reserve-mb", options.heap_reserve_mb,
                 "heap faulted in at start, so the first frames do not wait for page faults (0: none)")
      ->check(CLI::Range(0, 4096))
      ->capture_default_str();
  app.add_option("--log-level", options.log_level, "trace, debug, info, warn, error or off")
      ->check(CLI::IsMember({"trace", "debug", "info", "warn", "error", "off"}))
      ->capture_default_str();
}

void add_upstream_timeout_option(CLI::App& app, double& timeout_s) {
  app.add_option("--upstream-timeout", timeout_s,
                 "give up (exit 1) when no writer of any input has been matched for this long, s (0: wait forever); "
                 "for a restarted component whose stream may have ended meanwhile")
      ->check(non_negative_finite())
      ->capture_default_str();
}

void finalize(NodeOptions& options, const std::string& component) {
  options.dds.mode = parse_delivery_mode(options.mode);
  options.dds.participant_name = component;
  init_logging(component, options.log_level);
  prefault_heap(static_cast<std::size_t>(options.heap_reserve_mb));
}

}  // namespace uavmot::dds
