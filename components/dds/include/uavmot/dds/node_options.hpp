#pragma once
// Command-line options every DDS process shares: domain, profiles, transport, delivery mode.

#include <string>

#include <CLI/CLI.hpp>

#include "uavmot/dds/participant.hpp"

namespace uavmot::dds {

struct NodeOptions {
  DdsOptions dds;
  std::string mode = "lossless";
  std::string log_level = "info";
  int wait_subscribers = 0;  // lossless: publish only while this many readers are matched
  // Heap faulted in at start (uavmot/core/memory.hpp); 0 for tools that handle no frames.
  int heap_reserve_mb = 64;
};

// Adds --domain, --qos-profiles, --transport, --discovery-server, --mode, --wait-subscribers,
// --heap-reserve-mb, --log-level. Call finalize() after parsing.
void add_node_options(CLI::App& app, NodeOptions& options);
void finalize(NodeOptions& options, const std::string& component);

// Adds --upstream-timeout (seconds, 0 = wait forever; dds/upstream_watch.hpp) to a component that
// reads the chain. The launch profiles pass it to respawned components only.
void add_upstream_timeout_option(CLI::App& app, double& timeout_s);

}  // namespace uavmot::dds
