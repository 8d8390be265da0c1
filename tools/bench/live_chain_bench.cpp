// Live chain benchmark: end-to-end latency and per-component CPU time of the distributed chain.
//
//   uavmot-bench-live --input SEQ [--profile bringup/local.yaml] [--domain 48] [--out DIR] [--json OUT]
//
// Starts `uavmot launch PROFILE --input SEQ --set mode=live` (the source publishes at the input's
// native rate) and, in this process, subscribes to uavmot/tracks and uavmot/health:
//   - latency of every track list = its DDS source timestamp (when tracking wrote it) - capture_time_ns
//     (both wall clock, one host): frame due at the camera -> tracks published; also arrival here - capture;
//   - CPU time (utime + stime from /proc/<pid>/stat) of every component, sampled every 100 ms
//     using the pids from the health reports, the last sample kept;
//   - frames and drops per component from their last health report.
// Prints a table (and JSON with --json). Exit 1 when the launch failed.

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <thread>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "healthPubSubTypes.h"
#include "tracksPubSubTypes.h"
#include "uavmot/build_paths/build_paths.hpp"
#include "uavmot/core/app.hpp"
#include "uavmot/core/logging.hpp"
#include "uavmot/dds/node_support.hpp"
#include "uavmot/dds/participant.hpp"

namespace uavmot {
namespace {
namespace fs = std::filesystem;

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<size_t>(p * static_cast<double>(v.size() - 1) + 0.5))];
}

// utime + stime of a process in seconds; negative when it is gone.
double cpu_seconds(uint32_t pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
  std::string line;
  if (!std::getline(in, line)) return -1.0;
  // Fields after the ")" that closes the command name: state is field 3, utime 14, stime 15.
  std::istringstream rest(line.substr(line.rfind(')') + 2));
  std::string field;
  double utime = 0, stime = 0;
  for (int i = 3; i <= 15 && rest >> field; ++i) {
    if (i == 14) utime = std::stod(field);
    if (i == 15) stime = std::stod(field);
  }
  return (utime + stime) / static_cast<double>(::sysconf(_SC_CLK_TCK));
}

struct Component {
  msg::ComponentHealth last;
  std::map<uint32_t, double> cpu_by_pid;  // respawns get a pid of their own
  double cpu() const {
    double s = 0;
    for (const auto& [pid, c] : cpu_by_pid) s += c;
    return s;
  }
};

int bench_main(int argc, char** argv) {
  std::string input, profile = build_paths::source_dir() + "/bringup/local.yaml", out_dir, json_out;
  int domain = 48;
  double timeout_s = 600;
  return run_app(argc, argv, "bench-live", "end-to-end latency and CPU time of the chain in live mode", [&](CLI::App& app) {
    app.add_option("--input", input, "sequence to run (e.g. made by uavmot sim)")->required();
    app.add_option("--profile", profile, "bringup profile")->capture_default_str();
    app.add_option("--domain", domain, "DDS domain for this run")->capture_default_str();
    app.add_option("--out", out_dir, "launch output folder (default: a temporary one)");
    app.add_option("--json", json_out, "also write the figures as JSON here");
    app.add_option("--timeout", timeout_s, "give up after this many seconds")->capture_default_str();
    return [&]() -> int {
      init_logging("bench-live", "warn");
      if (out_dir.empty()) out_dir = (fs::temp_directory_path() / fmt::format("uavmot-bench-live-{}", ::getpid())).string();
      dds::DdsOptions o;
      o.domain_id = domain;
      o.mode = dds::DeliveryMode::Live;
      o.participant_name = "bench-live";
      dds::Participant participant(o);
      auto tracks = participant.make_reader<msg::TrackListPubSubType>(dds::kTracksTopic, dds::TopicClass::Chain);
      auto health = participant.make_reader<msg::ComponentHealthPubSubType>(dds::kHealthTopic, dds::TopicClass::Health);

      const std::string uavmot = (fs::read_symlink("/proc/self/exe").parent_path() / "uavmot").string();
      std::vector<std::string> args{uavmot, "launch", profile, "--input", input, "--out", out_dir,
                                    "--set", "mode=live", "--set", fmt::format("domain={}", domain)};
      const pid_t launch = ::fork();
      if (launch == 0) {
        std::vector<char*> cargs;
        ::dup2(STDERR_FILENO, STDOUT_FILENO);  // the launch's log to stderr; stdout is for the figures
        for (auto& a : args) cargs.push_back(a.data());
        cargs.push_back(nullptr);
        ::execv(cargs[0], cargs.data());
        ::_exit(127);
      }
      std::cerr << "bench-live: " << fmt::format("{}", fmt::join(args, " ")) << "\n";

      std::vector<double> latencies_ms, arrival_ms;
      nlohmann::json per_frame = nlohmann::json::array();  // [frame index, published - capture ms, arrival - capture ms]
      std::map<std::string, Component> components;
      int64_t first_capture = 0, last_capture = 0;
      int status = 0;
      const auto start = std::chrono::steady_clock::now();
      auto last_cpu_sample = start;
      bool exited = false;
      while (!exited) {
        tracks->wait_for_data(std::chrono::milliseconds(20));
        msg::TrackList t;
        eprosima::fastdds::dds::SampleInfo info;
        while (tracks->take(t, &info)) {
          if (t.end_of_stream()) continue;
          // When tracking wrote it (DDS source timestamp, wall clock), so a stall of this process
          // does not count; the arrival here is kept beside it.
          const int64_t published_ns = static_cast<int64_t>(info.source_timestamp.seconds()) * 1'000'000'000LL +
                                       info.source_timestamp.nanosec();
          latencies_ms.push_back(static_cast<double>(published_ns - t.capture_time_ns()) / 1e6);
          arrival_ms.push_back(dds::latency_ms_since(t.capture_time_ns()));
          per_frame.push_back({t.frame_index(), latencies_ms.back(), arrival_ms.back()});
          if (!first_capture) first_capture = t.capture_time_ns();
          last_capture = t.capture_time_ns();
        }
        msg::ComponentHealth h;
        while (health->take(h)) components[h.component_name().to_string()].last = h;
        const auto now = std::chrono::steady_clock::now();
        if (now - last_cpu_sample > std::chrono::milliseconds(100)) {
          last_cpu_sample = now;
          for (auto& [name, c] : components) {
            const double cpu = cpu_seconds(c.last.pid());
            if (cpu >= 0) c.cpu_by_pid[c.last.pid()] = cpu;
          }
        }
        if (::waitpid(launch, &status, WNOHANG) == launch) exited = true;
        if (now - start > std::chrono::duration<double>(timeout_s)) {
          std::cerr << "bench-live: timeout; stopping the launch\n";
          ::kill(launch, SIGINT);
          ::waitpid(launch, &status, 0);
          exited = true;
        }
      }
      // Reports sent while the processes finished.
      msg::ComponentHealth h;
      while (health->take(h)) components[h.component_name().to_string()].last = h;
      const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      const double span_s = static_cast<double>(last_capture - first_capture) / 1e9;

      nlohmann::json j;
      j["input"] = input;
      j["wall_s"] = wall_s;
      j["track_lists"] = latencies_ms.size();
      j["latency_ms"] = {{"median", percentile(latencies_ms, 0.5)}, {"p99", percentile(latencies_ms, 0.99)},
                         {"max", percentile(latencies_ms, 1.0)}};
      fmt::print("input {}\ntrack lists received: {} over {:.1f} s of capture time\n", input, latencies_ms.size(), span_s);
      fmt::print("end-to-end latency (capture -> tracks published): median {:.1f} ms, p99 {:.1f} ms, max {:.1f} ms\n",
                 percentile(latencies_ms, 0.5), percentile(latencies_ms, 0.99), percentile(latencies_ms, 1.0));
      fmt::print("                   (capture -> tracks taken here): median {:.1f} ms, p99 {:.1f} ms\n",
                 percentile(arrival_ms, 0.5), percentile(arrival_ms, 0.99));
      j["arrival_latency_ms"] = {{"median", percentile(arrival_ms, 0.5)}, {"p99", percentile(arrival_ms, 0.99)}};
      fmt::print("{:<13} {:>9} {:>9} {:>8} {:>9} {:>8} {:>7}\n", "component", "frames in", "out", "dropped", "cpu s", "cpu %",
                 "proc ms");
      static const char* const kOrder[] = {"source", "motion", "segmentation", "tracking", "sink"};
      for (const char* name : kOrder) {
        auto it = components.find(name);
        if (it == components.end()) {
          fmt::print("{:<13} (no health report)\n", name);
          continue;
        }
        const auto& c = it->second;
        fmt::print("{:<13} {:>9} {:>9} {:>8} {:>9.2f} {:>7.0f}% {:>7.1f}\n", name, c.last.frames_in(), c.last.frames_out(),
                   c.last.dropped(), c.cpu(), 100.0 * c.cpu() / std::max(span_s, 1e-9), c.last.processing_ms());
        j["components"][name] = {{"frames_in", c.last.frames_in()}, {"frames_out", c.last.frames_out()},
                                 {"dropped", c.last.dropped()}, {"cpu_s", c.cpu()},
                                 {"respawns", c.cpu_by_pid.empty() ? 0 : c.cpu_by_pid.size() - 1}};
      }
      j["latency_per_frame"] = per_frame;
      const bool ok = WIFEXITED(status) && WEXITSTATUS(status) == 0;
      j["launch_ok"] = ok;
      if (!json_out.empty()) std::ofstream(json_out) << j.dump(2) << "\n";
      if (!ok) std::cerr << "bench-live: the launch failed (see its log above)\n";
      return ok ? kExitOk : kExitFailure;
    };
  });
}

}  // namespace
}  // namespace uavmot

int main(int argc, char** argv) { return uavmot::bench_main(argc, argv); }
