#include "uavmot/launch/dds_health_monitor.hpp"

#include <unistd.h>

#include <set>
#include <tuple>

#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include "uavmot/dds/node_options.hpp"

namespace uavmot::launch {
namespace {

// The DDS options a uavmot process was started with, read the way it reads them itself.
dds::DdsOptions dds_options_of(const std::vector<std::string>& args) {
  CLI::App app;
  app.allow_extras();
  dds::NodeOptions node;
  dds::add_node_options(app, node);
  std::vector<std::string> reversed(args.rbegin(), args.rend());  // CLI11 parses a vector back to front
  try {
    app.parse(reversed);
  } catch (const CLI::ParseError&) {
    // Not a uavmot node's command line: its defaults then.
  }
  node.dds.mode = dds::DeliveryMode::Lossless;
  node.dds.participant_name = "launch-watchdog";
  return node.dds;
}

}  // namespace

DdsHealthMonitor::DdsHealthMonitor(const std::vector<std::vector<std::string>>& command_lines) {
  char host[64] = {};
  ::gethostname(host, sizeof(host) - 1);  // as HealthReporter does
  host_ = host;
  std::set<std::tuple<int, std::string, std::string, std::string>> seen;
  for (const auto& args : command_lines) {
    const auto o = dds_options_of(args);
    if (!seen.insert({o.domain_id, o.participant_profile, o.discovery_server, o.profiles_file}).second) continue;
    Endpoint e;
    e.participant = std::make_unique<dds::Participant>(o);
    e.reader = e.participant->make_reader<msg::ComponentHealthPubSubType>(dds::kHealthTopic, dds::TopicClass::Health);
    spdlog::info("watchdog: watching {} on domain {} ({})", dds::kHealthTopic, o.domain_id, o.participant_profile);
    endpoints_.push_back(std::move(e));
  }
}

DdsHealthMonitor::~DdsHealthMonitor() {
  for (auto& e : endpoints_) e.reader.reset();  // readers before their participant
}

void DdsHealthMonitor::poll() {
  msg::ComponentHealth sample;
  for (auto& e : endpoints_) {
    while (e.reader->take(sample)) {
      if (sample.host() != host_) continue;  // a pid is this host's only (a downlink forwards the UAV's reports)
      LastReport& r = last_[static_cast<pid_t>(sample.pid())];
      r.arrived = std::chrono::steady_clock::now();
      r.ended = sample.state() == msg::ComponentState::FINISHED || sample.state() == msg::ComponentState::FAILED;
    }
  }
}

std::optional<double> DdsHealthMonitor::silent_s(pid_t pid) const {
  const auto it = last_.find(pid);
  if (it == last_.end() || it->second.ended) return std::nullopt;
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - it->second.arrived).count();
}

}  // namespace uavmot::launch
