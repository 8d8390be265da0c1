#pragma once
// The launcher's watchdog view of uavmot/health: readers on every DDS setting (domain, transport,
// discovery server) that the watched processes report on, taken from their own command lines, so
// every profile (one host, air and ground) is watched where its processes report. One reader per
// watched component's partition: a report counts only for the component that may send it
// (health_partitions.hpp), so with security on no node can keep another's watchdog quiet.

#include <chrono>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "healthPubSubTypes.h"
#include "uavmot/dds/participant.hpp"
#include "uavmot/launch/supervisor.hpp"

namespace uavmot::launch {

class DdsHealthMonitor final : public HealthMonitor {
 public:
  struct Watched {
    std::string component;          // the process's command, e.g. "motion"
    std::vector<std::string> args;  // its arguments (without the program)
  };
  // `profiles_file`: the launcher's own QoS profiles (its identity with security on); empty: the
  // processes' default.
  DdsHealthMonitor(const std::vector<Watched>& watched, const std::string& profiles_file);
  ~DdsHealthMonitor() override;

  void poll() override;
  std::optional<double> silent_s(pid_t pid, const std::string& component) const override;
  bool reported(pid_t pid, const std::string& component) const override;

 private:
  struct Endpoint {
    std::unique_ptr<dds::Participant> participant;
    std::map<std::string, std::unique_ptr<dds::TopicReader<msg::ComponentHealthPubSubType>>> readers;  // by partition
  };
  struct LastReport {
    std::chrono::steady_clock::time_point arrived;
    bool ended = false;  // finished or failed: silent on purpose
  };
  std::string host_;
  std::vector<Endpoint> endpoints_;
  std::map<std::pair<pid_t, std::string>, LastReport> last_;  // by pid and component
};

}  // namespace uavmot::launch
