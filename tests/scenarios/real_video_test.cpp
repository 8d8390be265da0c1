// The whole chain on the real aerial clips shipped in data/ (no ground truth). Almost everything in
// them is static: buildings, trees, sheds, containers, parked vehicles. Issue 17: at most 0.5
// confirmed boxes per frame on such things (before the plane + parallax step, the ground-speed
// floor and the border rule: 167 per frame on CLIF, 28 on aphill_short). Every confirmed box is
// counted as false here, so the bound is stricter than the issue's: the one moving car seen by a
// person in these clips (aphill 1 fps, frames 150-180, docs/benchmarks/real_video.md) has boxes too.
// CLIF's city has many cars driving: since the segmentation places blob-less clusters on their
// motion evidence (session 44) it has 0.56 confirmed boxes per frame, 0.47 before; of its seven
// longest new tracks four were things driving, two a building's shadow and a parked car, one not
// clear (looked at frame by frame, docs/benchmarks/real_video.md). Its bound is 0.6.
// The same figures come from `tools/real_video_check.sh`.

#include <gtest/gtest.h>

#include <chrono>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "child_process.hpp"
#include "obb_rows.hpp"
#include "uavmot/build_paths/build_paths.hpp"

namespace uavmot {
namespace {

using testing::binary;
using testing::ChildProcess;
using testing::fresh_dir;
using testing::read_file;

struct ClipRun {
  int frames = 0;
  std::vector<testing::ObbRow> boxes;
  double confirmed_per_frame() const {
    const auto n = std::count_if(boxes.begin(), boxes.end(), [](const testing::ObbRow& b) { return b.state == "confirmed"; });
    return static_cast<double>(n) / std::max(1, frames);
  }
};

ClipRun process(const std::string& clip, const std::string& out, const std::string& config = "") {
  std::vector<std::string> argv = {binary("uavmot"), "process", build_paths::data_dir() + "/" + clip, "--out", out, "--quiet"};
  if (!config.empty()) argv.insert(argv.end(), {"--config", config});
  ChildProcess p(argv, out + ".log");
  const auto code = p.wait(std::chrono::minutes(10));
  EXPECT_TRUE(code.has_value() && *code == 0) << clip << ":\n" << p.log();
  ClipRun run;
  run.frames = nlohmann::json::parse(read_file(out + "/summary.json")).at("frames").get<int>();
  run.boxes = testing::read_obb_rows(out + "/tracks_obb.csv");
  return run;
}

TEST(RealVideoScenario, TheRealClipsGiveFewConfirmedBoxesPerFrame) {
  const std::string dir = fresh_dir("real_video_scenario");
  struct Clip {
    std::string path;
    int frames;
    double max_boxes_per_frame;
  };
  const std::vector<Clip> clips = {
      {"aphill/aphill_short.ts", 48, 0.5}, {"aphill/aphill_240_1fps_crf32.mp4", 310, 0.5}, {"clif2007/jpg", 250, 0.6}};
  for (const auto& [clip, frames, bound] : clips) {
    const ClipRun run = process(clip, dir + "/clip" + std::to_string(frames));
    std::printf("%s: %d frames, %.2f confirmed boxes per frame\n", clip.c_str(), run.frames, run.confirmed_per_frame());
    EXPECT_EQ(run.frames, frames) << clip;
    EXPECT_LE(run.confirmed_per_frame(), bound) << clip;
  }
}

TEST(RealVideoScenario, TheCarDrivingPastTheShedsIsTracked) {
  // aphill 1 fps, frames 170-182: a dark car drives down the yard between the sheds at about
  // 4 m/s (looked at frame by frame; it starts near (135, 95) and leaves near (150, 160)). At one
  // frame a second it moves ~12 px a frame and its tracks mostly coast between region hits.
  const std::string dir = fresh_dir("real_video_scenario_mover");
  const ClipRun run = process("aphill/aphill_240_1fps_crf32.mp4", dir + "/aphill_1fps");
  int confirmed = 0, live = 0;
  for (const auto& b : run.boxes) {
    if (b.frame < 170 || b.frame > 182 || b.cx < 100 || b.cx > 210 || b.cy < 60 || b.cy > 180 || !(b.speed_mps >= 2.0)) continue;
    confirmed += b.state == "confirmed";
    live += b.state == "confirmed" || b.state == "coasting";
  }
  EXPECT_GE(confirmed, 1) << "confirmed boxes moving with the car in frames 170-182";
  EXPECT_GE(live, 8) << "confirmed or coasting boxes moving with the car in frames 170-182";
}

TEST(RealVideoScenario, TheApertureCheckHoldsTheEdgesOfStructure) {
  // motion.aperture_ratio (docs/motion.md): a feature whose centre is a line along its motion does not
  // move, where cars are at least aperture_min_car_px long (aphill_short's KLV gives 4.8 cm/px: 93 px).
  // Its boxes, all on roofs and containers, go from 22 (0.46 per frame) to 4 with it.
  const std::string dir = fresh_dir("real_video_scenario_aperture");
  const std::string off = dir + "/aperture_off.yaml";
  std::ofstream(off) << "motion:\n  aperture_ratio: 0\n";
  const double with = process("aphill/aphill_short.ts", dir + "/with").confirmed_per_frame();
  const double without = process("aphill/aphill_short.ts", dir + "/without", off).confirmed_per_frame();
  std::printf("aphill_short: %.2f confirmed boxes per frame, %.2f without the aperture check\n", with, without);
  EXPECT_LE(with, 0.15);
  EXPECT_GE(without, 0.3) << "the clip no longer needs the check: this test proves nothing";
}

}  // namespace
}  // namespace uavmot
