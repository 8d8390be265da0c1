#pragma once
// Runs the processes of a resolved profile, in the spirit of ROS 2 launch:
// - starts them in profile order, each in its own process group;
// - prefixes every line a process prints with its name;
// - respawns a failed process (non-zero exit or signal) after its delay, up to max_respawns;
// - a required process that exits ends the launch; if it failed, the launch exits non-zero;
// - a stop_on_failure process that fails (after its respawns) ends the launch with a non-zero exit;
// - on SIGINT/SIGTERM stops everything in reverse start order: SIGINT, then SIGKILL after a grace period.

#include <string>

#include "uavmot/launch/profile.hpp"

namespace uavmot::launch {

struct SupervisorOptions {
  std::string bin_dir;              // where uavmot-<command> programs are
  double shutdown_grace_s = 10.0;   // per process, before SIGKILL
};

class Supervisor {
 public:
  // Throws InputError when a command's program does not exist (before anything is started).
  Supervisor(Profile resolved, SupervisorOptions options);
  // Returns the launch's exit code: 0, or 1 when a required or stop_on_failure process failed.
  int run();

 private:
  Profile profile_;
  SupervisorOptions options_;
  std::vector<std::string> programs_;
};

}  // namespace uavmot::launch
