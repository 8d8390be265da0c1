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
};

// Adds --domain, --qos-profiles, --transport, --mode, --log-level. Call finalize() after parsing.
void add_node_options(CLI::App& app, NodeOptions& options);
void finalize(NodeOptions& options, const std::string& component);

}  // namespace uavmot::dds
