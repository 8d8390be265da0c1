// uavmot-launch: starts the processes of a bringup profile and supervises them.
//   uavmot launch bringup/local.yaml --input SEQ --out DIR [--set name=value ...]

#include <filesystem>
#include <memory>
#include <sstream>
#include <iostream>

#include <unistd.h>

#include <spdlog/spdlog.h>

#include "uavmot/core/app.hpp"
#include "uavmot/core/error.hpp"
#include "uavmot/core/logging.hpp"
#include "uavmot/core/shutdown.hpp"
#include "uavmot/launch/dds_health_monitor.hpp"
#include "uavmot/launch/profile.hpp"
#include "uavmot/launch/supervisor.hpp"
#include "uavmot/source/frame_source.hpp"

namespace uavmot {
namespace {
namespace fs = std::filesystem;

std::string number(double v) {
  std::ostringstream s;
  s.precision(10);
  s << v;
  return s.str();
}

// The watchdog's QoS profiles: the launcher's own in the profile's qos_dir (with security on, its
// identity, which may read every component's health); empty (the default file) without a qos_dir.
std::string watchdog_profiles(const launch::Profile& resolved) {
  const auto it = resolved.variables.find("qos_dir");
  if (it == resolved.variables.end() || it->second.empty()) return "";
  const fs::path file = fs::path(it->second) / "launch.xml";
  if (!fs::exists(file)) {
    throw InputError("qos_dir '" + it->second + "' has no launch.xml (the launcher's identity for its watchdog): make it "
                     "again with tools/make_security.sh");
  }
  return fs::absolute(file).string();
}

int launch_main(int argc, char** argv) {
  std::string profile_file, input, out_dir = "out/launch";
  std::vector<std::string> sets;
  double grace_s = 10.0;
  bool dry_run = false;
  return run_app(argc, argv, "launch", "start and supervise the processes of a bringup profile", [&](CLI::App& app) {
    app.add_option("profile", profile_file, "bringup profile, e.g. bringup/local.yaml")->required()->check(CLI::ExistingFile);
    app.add_option("--input", input, "video, image folder or MOTChallenge sequence (sets ${input}, ${gsd}, ${fps})");
    app.add_option("--out", out_dir, "output folder (sets ${out})")->capture_default_str();
    app.add_option("--set", sets, "override a profile variable: name=value (repeatable)");
    app.add_option("--grace", grace_s, "seconds a process gets to stop before SIGKILL")->capture_default_str();
    app.add_flag("--dry-run", dry_run, "print the resolved processes and exit");
    return [&]() -> int {
      init_logging("launch", "info");
      install_shutdown_handler();
      const auto profile = launch::load_profile(profile_file);
      std::map<std::string, std::string> vars;
      vars["out"] = out_dir;
      vars["profile_dir"] = fs::absolute(profile_file).parent_path().string();
      // A folder of this launch's own: respawned processes find what their predecessor left
      // (e.g. the tracker's state); a new launch never sees an old run's.
      const fs::path run_dir = fs::temp_directory_path() / ("uavmot-launch-" + std::to_string(::getpid()));
      vars["run_dir"] = run_dir.string();
      vars["gsd"] = "0.35";
      vars["fps"] = "25";
      if (!input.empty()) {
        vars["input"] = input;
        const auto info = source::open_frame_source({.path = input})->info();
        if (info.gsd_m > 0) vars["gsd"] = number(info.gsd_m);
        vars["fps"] = number(info.fps);
      }
      for (const auto& s : sets) {
        const auto eq = s.find('=');
        if (eq == std::string::npos || eq == 0) throw InputError("--set expects name=value, got '" + s + "'");
        vars[s.substr(0, eq)] = s.substr(eq + 1);
      }
      const auto resolved = launch::resolve(profile, vars);
      const std::string bin_dir = fs::read_symlink("/proc/self/exe").parent_path().string();
      launch::Supervisor supervisor(resolved, {bin_dir, grace_s});
      if (dry_run) {
        for (const auto& p : resolved.processes) {
          std::cout << p.name << ": uavmot " << p.command;
          for (const auto& a : p.args) std::cout << " " << a;
          if (p.common_args) for (const auto& a : resolved.common_args) std::cout << " " << a;
          if (p.respawn && !p.respawn_args.empty()) {
            std::cout << "  (respawned with";
            for (const auto& a : p.respawn_args) std::cout << " " << a;
            std::cout << ")";
          }
          std::cout << "\n";
        }
        return kExitOk;
      }
      // The watchdog reads uavmot/health where the processes with a hang_timeout report.
      std::vector<launch::DdsHealthMonitor::Watched> watched;
      for (const auto& p : resolved.processes) {
        if (p.hang_timeout_s <= 0) continue;
        watched.push_back({p.command, p.args});
        if (p.common_args) watched.back().args.insert(watched.back().args.end(), resolved.common_args.begin(), resolved.common_args.end());
      }
      std::unique_ptr<launch::DdsHealthMonitor> health;
      if (!watched.empty()) health = std::make_unique<launch::DdsHealthMonitor>(watched, watchdog_profiles(resolved));
      supervisor.set_health_monitor(health.get());
      std::error_code ec;
      fs::remove_all(run_dir, ec);
      const int code = supervisor.run();
      fs::remove_all(run_dir, ec);
      return code;
    };
  });
}

}  // namespace
}  // namespace uavmot

int main(int argc, char** argv) { return uavmot::launch_main(argc, argv); }
