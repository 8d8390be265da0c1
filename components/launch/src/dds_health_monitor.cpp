#include "uavmot/launch/dds_health_monitor.hpp"

#include <unistd.h>

#include <map>
#include <tuple>

#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include "uavmot/dds/health_partitions.hpp"
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

DdsHealthMonitor::DdsHealthMonitor(const std::vector<Watched>& watched, const std::string& profiles_file) {
  char host[64] = {};
  ::gethostname(host, sizeof(host) - 1);  // as HealthReporter does
  host_ = host;
  std::map<std::tuple<int, std::string, std::string, std::string>, size_t> endpoint_of;
  for (const auto& w : watched) {
    auto o = dds_options_of(w.args);
    if (!profiles_file.empty()) o.profiles_file = profiles_file;
    const auto key = std::make_tuple(o.domain_id, o.participant_profile, o.discovery_server, o.profiles_file);
    if (!endpoint_of.count(key)) {
      endpoint_of[key] = endpoints_.size();
      endpoints_.push_back({std::make_unique<dds::Participant>(o), {}});
    }
    Endpoint& e = endpoints_[endpoint_of[key]];
    const std::string partition = dds::health_partition(w.component);
    if (e.readers.count(partition)) continue;
    e.readers[partition] =
        e.participant->make_reader_in<msg::ComponentHealthPubSubType>(partition, dds::kHealthTopic, dds::TopicClass::Health);
    spdlog::info("watchdog: watching {} of {} on domain {} ({})", dds::kHealthTopic, w.component, o.domain_id,
                 o.participant_profile);
  }
}

DdsHealthMonitor::~DdsHealthMonitor() {
  for (auto& e : endpoints_) e.readers.clear();  // readers before their participant
}

void DdsHealthMonitor::poll() {
  msg::ComponentHealth sample;
  for (auto& e : endpoints_) {
    for (auto& [partition, reader] : e.readers) {
      while (reader->take(sample)) {
        if (sample.host() != host_) continue;  // a pid is this host's only (a downlink forwards the UAV's reports)
        const std::string component = sample.component_name().to_string();
        if (!dds::health_report_trusted(partition, component)) continue;  // a report in another's name
        const std::pair<pid_t, std::string> key{static_cast<pid_t>(sample.pid()), component};
        if (!last_.count(key)) spdlog::info("watchdog: first health report of {} (pid {})", component, key.first);
        LastReport& r = last_[key];
        r.arrived = std::chrono::steady_clock::now();
        r.ended = sample.state() == msg::ComponentState::FINISHED || sample.state() == msg::ComponentState::FAILED;
      }
    }
  }
}

std::optional<double> DdsHealthMonitor::silent_s(pid_t pid, const std::string& component) const {
  const auto it = last_.find({pid, component});
  if (it == last_.end() || it->second.ended) return std::nullopt;
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - it->second.arrived).count();
}

bool DdsHealthMonitor::reported(pid_t pid, const std::string& component) const { return last_.count({pid, component}) > 0; }

}  // namespace uavmot::launch
