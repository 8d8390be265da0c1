#pragma once
// Helpers for tests that launch bringup/local.yaml and disturb it: the undisturbed run to compare
// with, which pid the launcher gave a process, how far the sink's files are, a signal to a component
// once they are that far, the tracks of a run.

#include <signal.h>

#include <chrono>
#include <cstdlib>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core/types.hpp>

#include "child_process.hpp"
#include "uavmot/build_paths/build_paths.hpp"

namespace uavmot::testing {

inline const std::string kLocalProfile = build_paths::source_dir() + "/bringup/local.yaml";

// The pid of the latest start of `name` in a launcher's log, or -1.
inline int launched_pid(const std::string& log, const std::string& name) {
  const std::regex started("started " + name + R"( \(pid (\d+)\))");
  int pid = -1;
  for (auto it = std::sregex_iterator(log.begin(), log.end(), started); it != std::sregex_iterator(); ++it) {
    pid = std::stoi((*it)[1]);
  }
  return pid;
}

// The frame of the last complete line of a results file such as tracks_obb.csv (0 before any).
inline int last_frame_written(const std::string& file) {
  const std::string text = read_file(file);
  if (text.size() < 2) return 0;
  const auto start = text.rfind('\n', text.size() - 2);
  return start == std::string::npos ? std::atoi(text.c_str()) : std::atoi(text.c_str() + start + 1);
}

// `uavmot launch bringup/local.yaml --input INPUT --out OUT` with SETS as `--set` values.
inline std::vector<std::string> local_launch(const std::string& input, const std::string& out,
                                             const std::vector<std::string>& sets) {
  std::vector<std::string> argv = {binary("uavmot"), "launch", kLocalProfile, "--input", input, "--out", out};
  for (const auto& set : sets) argv.insert(argv.end(), {"--set", set});
  return argv;
}

// The `paper` sequence of seed 3 with FRAMES frames in ROOT/paper, and its launch of
// bringup/local.yaml, undisturbed, into ROOT/undisturbed with SETS (`--set` values: at least the
// domain): the run a disturbed launch is compared with. Fails the test fatally when either fails
// (callers: ASSERT_NO_FATAL_FAILURE); LOG, when given, gets the launch's log.
inline void run_undisturbed_paper(const std::string& root, int frames, const std::vector<std::string>& sets,
                                  std::string* log = nullptr) {
  ChildProcess sim({binary("uavmot-sim"), "--preset", "paper", "--seed", "3", "--frames", std::to_string(frames), "--out",
                    root + "/paper"},
                   root + "/sim.log");
  ASSERT_EQ(sim.wait(std::chrono::seconds(180)), 0) << sim.log();
  ChildProcess undisturbed(local_launch(root + "/paper", root + "/undisturbed", sets), root + "/undisturbed.log");
  ASSERT_EQ(undisturbed.wait(std::chrono::seconds(300)), 0) << undisturbed.log();
  if (log != nullptr) *log = undisturbed.log();
}

// Sends SIGNUM to the launch's COMPONENT (the latest it started) once FILE (a results file such as
// tracks_obb.csv) has reached FRAME, polling every POLL. Returns the pid signalled and the frame FILE
// had then; pid -1 when the launch ended or TIMEOUT passed first (the caller asserts, with the log).
struct Signalled {
  int pid = -1;
  int frame = 0;
};
inline Signalled signal_when_written(ChildProcess& launch, const std::string& component, const std::string& file,
                                     int frame, int signum, std::chrono::milliseconds poll = std::chrono::milliseconds(5),
                                     std::chrono::seconds timeout = std::chrono::seconds(180)) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (std::chrono::steady_clock::now() < deadline && !launch.wait(std::chrono::milliseconds(0))) {
    const int pid = launched_pid(launch.log(), component);
    if (const int written = last_frame_written(file); pid > 0 && written >= frame) {
      if (::kill(pid, signum) != 0) {
        ADD_FAILURE() << "cannot signal " << component << " (pid " << pid << ")";
        return {};
      }
      return {pid, written};
    }
    std::this_thread::sleep_for(poll);
  }
  return {};
}

// frame -> id -> box (x, y, w, h), from a MOTChallenge tracks.txt
using TrackTable = std::map<int, std::map<int, cv::Rect2d>>;

inline TrackTable read_tracks(const std::string& file) {
  TrackTable table;
  std::istringstream in(read_file(file));
  for (std::string line; std::getline(in, line);) {
    std::vector<double> v;
    std::stringstream row(line);
    for (std::string cell; std::getline(row, cell, ',');) v.push_back(std::stod(cell));
    table[static_cast<int>(v[0])][static_cast<int>(v[1])] = {v[2], v[3], v[4], v[5]};
  }
  return table;
}

inline double iou(const cv::Rect2d& a, const cv::Rect2d& b) {
  const double inter = (a & b).area();
  return inter / (a.area() + b.area() - inter);
}

// Of the confirmed tracks of BEFORE (an undisturbed run) at frame PROBE that were there at frame
// EARLIER too (in view before a disturbance between them), how many AFTER has at PROBE with the same
// id on the same object (IoU > 0.5).
struct IdsKept {
  int compared = 0;
  int kept = 0;
};
inline IdsKept ids_kept(const TrackTable& before, const TrackTable& after, int probe, int earlier) {
  IdsKept n;
  const auto then = before.find(earlier);
  const auto now = before.find(probe);
  if (then == before.end() || now == before.end()) return n;
  const auto it = after.find(probe);
  for (const auto& [id, box] : now->second) {
    if (!then->second.count(id)) continue;  // not yet in view before the disturbance
    ++n.compared;
    if (it != after.end() && it->second.count(id) && iou(it->second.at(id), box) > 0.5) ++n.kept;
  }
  return n;
}

}  // namespace uavmot::testing
