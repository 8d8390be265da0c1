#pragma once
// A bringup profile: which processes to start, with which arguments and environment, and what
// to do when they exit (bringup/*.yaml; docs/launch.md).

#include <map>
#include <string>
#include <vector>

namespace uavmot::launch {

struct ProcessSpec {
  std::string name;
  std::string command;  // a uavmot subcommand (runs uavmot-<command>) or a path to a program
  std::vector<std::string> args;
  std::map<std::string, std::string> env;
  // "${view}" and the like: resolve() drops the process unless this becomes true/yes/on/1.
  std::string enabled = "true";
  // Topics it subscribes to. ${readers:TOPIC} is the number of enabled processes that read TOPIC,
  // so a writer's --wait-subscribers follows the processes that are switched on (viewer, recorder).
  std::vector<std::string> reads;
  bool common_args = true;     // append the profile's common_args
  bool required = false;         // its exit ends the launch (non-zero exit of the launch if it failed)
  bool stop_on_failure = false;  // its failure (after respawns) ends the launch with a non-zero exit
  bool respawn = false;        // restart after a failure (non-zero exit or signal)
  std::vector<std::string> respawn_args;  // appended to args when respawned (e.g. the sink's --resume)
  std::string respawn_delay = "1.0";  // seconds; a string until resolve() ("${var}" allowed), then respawn_delay_s
  double respawn_delay_s = 1.0;
  int max_respawns = 3;
  double start_delay_s = 0.2;  // pause after starting it, before the next one
  // Watchdog: once the process has reported on uavmot/health, reports that stop for this long while
  // it is alive mean it hangs; it is killed and handled like a crash (respawn policy). 0: off.
  // A string until resolve(), so a profile can write "${hang_timeout}"; then hang_timeout_s.
  std::string hang_timeout = "0";
  double hang_timeout_s = 0.0;
};

struct Profile {
  std::string file;
  std::string description;
  std::map<std::string, std::string> variables;  // defaults for ${name}; --set overrides; after resolve(): the values used
  std::vector<std::string> common_args;
  std::vector<ProcessSpec> processes;
};

// Throws InputError naming the file, line and key of anything invalid (unknown keys included).
Profile load_profile(const std::string& file);

// Replaces ${name} in every argument and environment value, drops processes whose `enabled`
// resolves to false and provides ${readers:TOPIC} (see ProcessSpec::reads). Throws InputError
// naming an undefined variable or a bad `enabled` value and the process that uses it.
Profile resolve(const Profile& profile, const std::map<std::string, std::string>& variables);

}  // namespace uavmot::launch
