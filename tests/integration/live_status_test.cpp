// Live mode, watched: the chain runs under `uavmot launch ... --set mode=live` and
// `uavmot status --once --json` sees every component with sensible figures, and the source keeps
// to the camera clock however fast the host is (under ASan it cannot publish every frame).

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <map>
#include <set>
#include <sstream>
#include <thread>
#include <utility>
#include <vector>

#include "child_process.hpp"
#include "uavmot/build_paths/build_paths.hpp"

namespace uavmot {
namespace {
using testing::binary;
using testing::ChildProcess;

const std::string kProfile = build_paths::source_dir() + "/bringup/local.yaml";
const std::set<std::string> kChain{"source", "motion", "segmentation", "tracking", "sink"};

// The rows of components that are running and really moving frames.
void collect_flowing(const nlohmann::json& table, std::map<std::string, nlohmann::json>& rows) {
  for (const auto& row : table) {
    if (row["state"] == "running" && !row["stale"].get<bool>() && row["rate_hz"].get<double>() > 0 &&
        row["frames_out"].get<uint64_t>() > 0) {
      // Bytes/s needs two reports in one poll's window: keep a row that has it over one that does not.
      auto& kept = rows[row["component"].get<std::string>()];
      if (kept.is_null() || row["bytes_per_s"].get<double>() > 0 || kept["bytes_per_s"].get<double>() <= 0) kept = row;
    }
  }
}

std::set<std::string> names(const std::map<std::string, nlohmann::json>& rows) {
  std::set<std::string> out;
  for (const auto& [name, row] : rows) out.insert(name);
  return out;
}

TEST(LiveStatus, StatusSeesEveryComponentOfALiveChain) {
  const std::string root = testing::fresh_dir("live_status");
  // 450 frames at the preset's 25 fps: eighteen seconds of live stream to look at.
  ChildProcess sim({binary("uavmot-sim"), "--preset", "paper", "--seed", "3", "--frames", "450", "--out", root + "/seq", "--quiet"},
                   root + "/sim.log");
  ASSERT_EQ(sim.wait(std::chrono::seconds(240)), 0) << sim.log();

  ChildProcess launch({binary("uavmot"), "launch", kProfile, "--input", root + "/seq", "--out", root + "/tracks", "--set",
                       "mode=live", "--set", "domain=46"},
                      root + "/launch.log");
  // Each `status --once` is a new DDS participant that discovers the five components within its
  // --wait; on a loaded host one may be found only by the next poll, so the polls add up.
  std::map<std::string, nlohmann::json> seen;
  nlohmann::json last_table;
  int polls = 0;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  auto source_rate_known = [&] { return seen.count("source") && seen.at("source")["bytes_per_s"].get<double>() > 0; };
  // The source's reports as (wall-clock stamp, index of the frame last published), one per poll:
  // how the index moves with the wall clock is the camera rate the source keeps to. From frame 2 on:
  // the camera clock starts once every reader has acknowledged frame 1.
  std::vector<std::pair<int64_t, int64_t>> source_clock;
  auto source_clock_span_s = [&] {
    return source_clock.size() < 2 ? 0.0 : (source_clock.back().first - source_clock.front().first) * 1e-9;
  };
  while ((names(seen) != kChain || !source_rate_known() || source_clock_span_s() < 3.0) &&
         std::chrono::steady_clock::now() < deadline) {
    ChildProcess status({binary("uavmot"), "status", "--once", "--json", "--wait", "3", "--domain", "46"},
                        root + "/status_" + std::to_string(++polls) + ".log");
    const auto code = status.wait(std::chrono::seconds(30));
    ASSERT_TRUE(code.has_value()) << "status --once did not exit";
    // stdout (the JSON line) and stderr (log lines, also starting with '[') share the log file.
    std::istringstream lines(status.log());
    for (std::string line; std::getline(lines, line);) {
      if (*code == 0 && nlohmann::json::accept(line)) {
        last_table = nlohmann::json::parse(line);
        collect_flowing(last_table, seen);
        for (const auto& row : last_table) {
          if (row["component"] == "source" && row["state"] == "running" && row["last_frame_index"].get<int64_t>() >= 2 &&
              (source_clock.empty() || row["stamp_ns"].get<int64_t>() > source_clock.back().first)) {
            source_clock.emplace_back(row["stamp_ns"].get<int64_t>(), row["last_frame_index"].get<int64_t>());
          }
        }
      }
    }
    if (launch.wait(std::chrono::milliseconds(0)).has_value()) break;
  }
  EXPECT_EQ(names(seen), kChain) << "last status table: " << last_table.dump(1) << "\nlaunch log:\n" << launch.log();

  // The camera clock: a live source passes over the frames it is late for, so the index it publishes
  // advances at the camera's 25 fps even when the host is too slow to publish every frame.
  ASSERT_GE(source_clock_span_s(), 3.0) << "fewer than two source reports 3 s apart; launch log:\n" << launch.log();
  const double camera_rate_hz = (source_clock.back().second - source_clock.front().second) / source_clock_span_s();
  EXPECT_NEAR(camera_rate_hz, 25.0, 3.0) << "frame index per second of wall clock, the source's reports from "
                                         << source_clock.front().second << " to " << source_clock.back().second;

  // Sensible values: the source never faster than the camera, latencies positive and bounded by the run.
  for (const auto& [name, row] : seen) {
    EXPECT_GT(row["pid"].get<int>(), 0) << name;
    EXPECT_FALSE(row["host"].get<std::string>().empty()) << name;
    EXPECT_GE(row["frames_in"].get<uint64_t>(), row["frames_out"].get<uint64_t>() > 0 ? 1u : 0u) << name;
    EXPECT_GE(row["latency_ms"].get<double>(), 0.0) << name;
    EXPECT_LT(row["latency_ms"].get<double>(), 60'000.0) << name;
    if (name == "source") {
      EXPECT_GT(row["rate_hz"].get<double>(), 0.0);
      EXPECT_LE(row["rate_hz"].get<double>(), 30.0) << "a live source publishes at most at the camera rate: " << row.dump();
      EXPECT_GT(row["bytes_per_s"].get<double>(), 0.0);
    }
  }
  EXPECT_EQ(launch.wait(std::chrono::seconds(120)), 0) << launch.log();
}

}  // namespace
}  // namespace uavmot
