#pragma once
// The launcher's watchdog view of uavmot/health: one reader per DDS setting (domain, transport,
// discovery server, profiles) that the watched processes report on, taken from their own command
// lines, so every profile (one host, air and ground) is watched where its processes report.

#include <chrono>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "healthPubSubTypes.h"
#include "uavmot/dds/participant.hpp"
#include "uavmot/launch/supervisor.hpp"

namespace uavmot::launch {

class DdsHealthMonitor final : public HealthMonitor {
 public:
  // `command_lines`: the arguments (without the program) of every process to watch.
  explicit DdsHealthMonitor(const std::vector<std::vector<std::string>>& command_lines);
  ~DdsHealthMonitor() override;

  void poll() override;
  std::optional<double> silent_s(pid_t pid) const override;

 private:
  struct Endpoint {
    std::unique_ptr<dds::Participant> participant;
    std::unique_ptr<dds::TopicReader<msg::ComponentHealthPubSubType>> reader;
  };
  struct LastReport {
    std::chrono::steady_clock::time_point arrived;
    bool ended = false;  // finished or failed: silent on purpose
  };
  std::string host_;
  std::vector<Endpoint> endpoints_;
  std::map<pid_t, LastReport> last_;
};

}  // namespace uavmot::launch
