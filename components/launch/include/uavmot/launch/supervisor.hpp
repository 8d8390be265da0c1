#pragma once
// Runs the processes of a resolved profile, in the spirit of ROS 2 launch:
// - starts them in profile order, each in its own process group;
// - prefixes every line a process prints with its name;
// - respawns a failed process (non-zero exit or signal) after its delay, up to max_respawns;
// - a required process that exits ends the launch; if it failed, the launch exits non-zero;
// - a stop_on_failure process that fails (after its respawns) ends the launch with a non-zero exit;
// - on SIGINT/SIGTERM stops everything in reverse start order: SIGINT, then SIGKILL after a grace period;
// - watchdog: a process with a hang_timeout whose health reports stop for that long while it is alive
//   (e.g. SIGSTOP, a deadlock of its whole process) is killed and handled like a crash.

#include <optional>
#include <string>
#include <sys/types.h>

#include "uavmot/launch/profile.hpp"

namespace uavmot::launch {

// What the watchdog knows of the health topic (uavmot/health, docs/status.md), per process id
// and component (the process's command: only the component itself may report as it).
class HealthMonitor {
 public:
  virtual ~HealthMonitor() = default;
  // Takes the reports that arrived since the last call.
  virtual void poll() = 0;
  // Seconds since the last report of `component` with `pid` arrived; nullopt before its first
  // report, and after it reported that it finished or failed (it stops reporting on purpose then).
  virtual std::optional<double> silent_s(pid_t pid, const std::string& component) const = 0;
  // Whether `component` with `pid` has reported at all (a process that never does hangs too).
  virtual bool reported(pid_t pid, const std::string& component) const = 0;
};

struct SupervisorOptions {
  std::string bin_dir;              // where uavmot-<command> programs are
  double shutdown_grace_s = 10.0;   // per process, before SIGKILL
  HealthMonitor* health = nullptr;  // the watchdog's view of uavmot/health; null: no watchdog
};

class Supervisor {
 public:
  // Throws InputError when a command's program does not exist (before anything is started).
  Supervisor(Profile resolved, SupervisorOptions options);
  // Returns the launch's exit code: 0, or 1 when a required or stop_on_failure process failed.
  int run();
  // The watchdog's view of the health topic (owned by the caller; null: no watchdog).
  void set_health_monitor(HealthMonitor* health) { options_.health = health; }

 private:
  Profile profile_;
  SupervisorOptions options_;
  std::vector<std::string> programs_;
};

}  // namespace uavmot::launch
