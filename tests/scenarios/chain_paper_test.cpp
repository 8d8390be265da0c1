// The whole chain as a user runs it: `uavmot sim --preset paper --seed N`, `uavmot process` with
// the default configuration, scored by `uavmot eval` (paper Tables I/II, TrackEval), on three seeds
// (one seed is what the chain was once tuned on; docs/tracking.md, "Validation protocol"). The
// figures are held at the level the seeds 1-3 reach (mean, and the worst seed for the correct
// rate), with a small margin, so a change that costs accuracy on any of them fails here. Issue 18's
// targets (>= 95 % correct on every seed) are not met yet; docs/tracking.md lists the gap.
// The `small` (8 x 3 px cars at 0.6 m/px) and `lowsnr` presets are held the same way below.

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "child_process.hpp"

namespace uavmot {
namespace {

using testing::binary;
using testing::ChildProcess;
using testing::fresh_dir;

int run(const std::vector<std::string>& argv, const std::string& log) {
  ChildProcess p(argv, log);
  const auto code = p.wait(std::chrono::minutes(8));
  EXPECT_TRUE(code.has_value()) << argv[0] << " did not finish:\n" << p.log();
  EXPECT_EQ(code.value_or(-1), 0) << p.log();
  return code.value_or(-1);
}

// frames 0: the preset's own length.
nlohmann::json score_seed(int seed, const std::string& preset = "paper", int frames = 0) {
  const std::string dir = fresh_dir("chain_" + preset + "_scenario_seed" + std::to_string(seed));
  const std::string seq = dir + "/" + preset, out = dir + "/out";
  std::vector<std::string> sim = {binary("uavmot"), "sim", "--preset", preset, "--seed", std::to_string(seed), "--out", seq, "--quiet"};
  if (frames > 0) sim.insert(sim.end(), {"--frames", std::to_string(frames)});
  EXPECT_EQ(run(sim, dir + "/sim.log"), 0);
  EXPECT_EQ(run({binary("uavmot"), "process", seq, "--out", out, "--quiet"}, dir + "/process.log"), 0);
  EXPECT_EQ(run({binary("uavmot"), "eval", "--seq", seq, "--pred", out + "/tracks.txt", "--obb", out + "/tracks_obb.csv",
                 "--json", out + "/eval.json"},
                dir + "/eval.log"),
            0);
  std::ifstream in(out + "/eval.json");
  return nlohmann::json::parse(in);
}

TEST(ChainPaperScenario, ThreeSeedsHoldTheirCorrectRatePrecisionAndFalseAlarms) {
  const std::vector<int> seeds = {1, 2, 3};
  double correct = 0, worst_correct = 1, over = 0, ex = 0, ey = 0, ew = 0, el = 0, fa = 0, mota = 0;
  int under = 0;
  for (const int seed : seeds) {
    const auto e = score_seed(seed);
    const auto& c = e.at("completeness");
    const auto& p = e.at("precision");
    const auto& f = e.at("false_alarms");
    ASSERT_GT(c.at("instances").get<int>(), 10000) << "seed " << seed;
    const double rate = c.at("correct_rate").get<double>();
    std::printf("paper seed %d: correct %.2f %%, over %.2f %%, under %d, e_x %.2f e_y %.2f e_w %.2f e_l %.2f px, "
                "false alarms %.2f / frame (%d on parked)\n",
                seed, 100 * rate, 100 * c.at("over_segmented_rate").get<double>(), c.at("under_segmented").get<int>(),
                p.at("error_x_px").get<double>(), p.at("error_y_px").get<double>(), p.at("error_width_px").get<double>(),
                p.at("error_length_px").get<double>(), f.at("per_frame").get<double>(), f.at("on_parked").get<int>());
    correct += rate / seeds.size();
    worst_correct = std::min(worst_correct, rate);
    over += c.at("over_segmented_rate").get<double>() / seeds.size();
    under += c.at("under_segmented").get<int>();
    ex += p.at("error_x_px").get<double>() / seeds.size();
    ey += p.at("error_y_px").get<double>() / seeds.size();
    ew += p.at("error_width_px").get<double>() / seeds.size();
    el += p.at("error_length_px").get<double>() / seeds.size();
    fa += f.at("per_frame").get<double>() / seeds.size();
    for (const auto& t : e.at("tracking")) {
      if (t.at("iou_threshold").get<double>() < 0.4) mota += t.at("MOTA").get<double>() / seeds.size();  // IoU 0.3
    }
  }
  // Seeds 1-3 on 2026-11-25 (tools/validate.sh --tuning --frames 250 paper): correct 95.27 / 89.95 / 92.41 %, over 0 / 69 / 0 instances,
  // under 0, false alarms 3.05 / 2.44 / 1.93 per frame, MOTA@0.3 0.912 / 0.848 / 0.911.
  // 2026-11-27, with the segmentation's shift check (docs/segmentation.md): correct 95.22 / 88.55 / 92.17 % (without it
  // 95.09 / 89.22 / 92.19), false alarms 1.26 / 2.48 / 1.54 per frame (without 1.86 / 2.32 / 1.73). The check was judged
  // on held-out seeds 100-104 of every preset (docs/tracking.md: paper 89.97 -> 90.02 %, false alarms 3.43 -> 2.74),
  // not on these three; the correct-rate bounds moved down by what seed 2 lost, the false-alarm bound down to what the
  // check holds (without it, 1.97 per frame fails it).
  // 2026-11-27, session 19, with the shadow correction (docs/segmentation.md, "Shadows"): correct 95.62 / 89.27 / 92.19 %
  // (before 95.22 / 88.55 / 92.17), e_x 0.90 / 1.26 / 0.73 px (before 1.29 / 1.51 / 1.08), e_y 0.73 / 0.94 / 0.67 px
  // (0.99 / 1.12 / 0.92), false alarms 1.15 / 1.96 / 0.97 per frame (1.26 / 2.48 / 1.54), over-segmentation 0.01 / 1.04 /
  // 0.01 %, MOTA@0.3 0.939 / 0.842 / 0.911. Judged on held-out seeds 100-104 of every preset first (docs/tracking.md).
  // Issue 18's position target (<= 1.2 px) is held here with the mean.
  // 2026-11-28, session 28, regions moved onto their features (docs/tracking.md): correct 95.61 / 89.78 / 93.73 %,
  // e_w 1.93 / 2.00 / 2.07 px, false alarms 1.05 / 1.99 / 1.37 per frame (0 / 0 / 17 boxes on parked vehicles).
  // 2026-11-29, session 34, creeping vehicles found below the speed floor (docs/motion.md, `creep_speed_factor`): correct
  // 96.09 / 91.72 / 94.06 % -> 96.33 / 92.26 / 94.90 %, false alarms 1.94 / 1.26 / 1.37 -> 1.96 / 1.65 / 1.40 per frame.
  // Seed 2's extra false alarms are one track beside a slow truck for 85 frames, held by ground corners the truck drags
  // but too far from its own moving corners for the rule's veto; the held-out seeds 100-104 gained 0.39 points for
  // 0.15 false alarms per frame (docs/tracking.md, session 34). The correct-rate bounds fail without the rule.
  // 2026-11-29, session 35, boxes moved onto their motion evidence (docs/segmentation.md, "Motion evidence"): correct
  // 96.33 / 92.26 / 94.90 % -> 96.50 / 92.96 / 94.91 %, false alarms 1.96 / 1.65 / 1.40 -> 1.53 / 0.98 / 1.33 per frame
  // (mean 1.67 -> 1.28; the false-alarm bound fails without it). Held-out seeds 100-104 first (docs/tracking.md).
  // 2026-12-06, session 37, the shadow taken out of the boxes' size too (docs/segmentation.md, "Shadows"): e_w
  // 1.98 / 2.12 / 2.10 -> 1.65 / 1.94 / 1.59 px, e_l 2.41 / 2.98 / 2.33 -> 1.86 / 2.71 / 1.64 px (the size bounds fail
  // without it), correct 96.50 / 92.96 / 94.91 -> 96.49 / 92.88 / 95.03 %, false alarms 1.53 / 0.98 / 1.33 -> 1.64 / 1.27 /
  // 1.32 per frame (mean 1.28 -> 1.41). Held-out seeds 100-109 first (docs/tracking.md, session 37).
  // 2026-12-06, session 39, the travel heading (docs/tracking.md): correct 96.49 / 92.88 / 95.03 -> 96.64 / 93.09 /
  // 94.94 %, false alarms 1.64 / 1.27 / 1.32 -> 0.94 / 1.17 / 1.35 per frame (mean 1.41 -> 1.15; the false-alarm bound
  // fails without it). Held-out seeds 100-109 first.
  // 2026-12-07, session 45, vehicles driving in across the image border confirm there (docs/tracking.md): correct
  // 96.81 / 92.99 / 95.09 -> 96.91 / 93.22 / 95.34 % (mean 94.96 -> 95.16, issue 18's 95 %; the bound fails without it).
  // Held-out seeds 100-109 first.
  EXPECT_GE(correct, 0.95);
  EXPECT_GE(worst_correct, 0.92);
  EXPECT_EQ(under, 0);
  EXPECT_LE(over, 0.005);
  EXPECT_LE(ex, 1.1);
  EXPECT_LE(ey, 1.0);
  EXPECT_LE(ew, 1.85);
  EXPECT_LE(el, 2.3);
  EXPECT_LE(fa, 1.3);
  EXPECT_GE(mota, 0.89);
}

// Correct rate (mean and worst) and false alarms per frame (mean) of seeds 1-3 of `preset` at 150
// frames, each seed printed.
struct SeedFigures {
  double correct = 0, worst_correct = 1, false_alarms = 0;
};
void score_seeds_1_to_3(const std::string& preset, SeedFigures& out, int min_instances = 5000) {
  const std::vector<int> seeds = {1, 2, 3};
  for (const int seed : seeds) {
    const auto e = score_seed(seed, preset, 150);
    const auto& c = e.at("completeness");
    ASSERT_GT(c.at("instances").get<int>(), min_instances) << preset << " seed " << seed;
    const double rate = c.at("correct_rate").get<double>();
    const double per_frame = e.at("false_alarms").at("per_frame").get<double>();
    std::printf("%s seed %d: correct %.2f %%, %.2f false alarms per frame\n", preset.c_str(), seed, 100 * rate, per_frame);
    out.correct += rate / seeds.size();
    out.worst_correct = std::min(out.worst_correct, rate);
    out.false_alarms += per_frame / seeds.size();
  }
}

// The automatic LK window (docs/motion.md, `lk_window_px`) is 7 px at 0.6 m/px: with the 11 px
// window of the other presets these seeds gave 60.37 / 64.37 / 64.93 % correct and 6.50 / 5.61 /
// 8.41 false alarms per frame (mean 63.2 %, 6.84); with 7 px 66.14 / 68.76 / 68.92 %, 4.55 / 5.09
// / 6.00 (mean 67.9 %, 5.21). With the lower speed floor in frames without 3-D structure
// (`flat_scene_speed_factor` 0.8, docs/motion.md) 67.37 / 69.53 / 69.62 %, 5.59 / 5.25 / 6.37
// (mean 68.8 %, 5.74). Sessions 31-34 brought them to 72.21 / 72.06 / 73.16 %, 5.03 / 5.66 / 6.05 (mean 72.5 %,
// 5.58); with the boxes moved onto their motion evidence (docs/segmentation.md, session 35: an 8 x 3 px road-grey car's
// blob is mostly its shadow) 74.24 / 73.86 / 75.25 %, 3.70 / 4.22 / 4.97 (mean 74.5 %, 4.30). With the travel heading
// (docs/tracking.md, session 39: a car with one feature gets its box's axis from where it drives, not from its blob)
// 75.52 / 75.45 / 75.98 %, 3.78 / 3.01 / 4.51 (mean 75.7 %, 3.77): all three bounds fail without it. Issue 18's
// target for `small` (>= 80 %) is not met yet.
TEST(ChainSmallScenario, ThreeSeedsOfEightPixelCarsHoldTheirCorrectRateAndFalseAlarms) {
  SeedFigures f;
  ASSERT_NO_FATAL_FAILURE(score_seeds_1_to_3("small", f));
  EXPECT_GE(f.correct, 0.75);
  EXPECT_GE(f.worst_correct, 0.745);
  EXPECT_LE(f.false_alarms, 4.1);
}

// `lowsnr` (contrast 0.6, noise sigma 6, JPEG 70, 55 % dark cars): most missed cars had no corner
// above the absolute response. The corner threshold now follows the frame's contrast and faded
// corners do not start moving in such frames (docs/motion.md, `contrast_reference_grey`,
// `faded_corner_ratio`). Seeds 1-3, 150 frames: before 62.65 / 61.78 / 67.04 % correct, 4.63 /
// 3.27 / 3.27 false alarms per frame (mean 63.8 %, 3.72); with it 83.12 / 77.18 / 79.22 %, 4.93 /
// 4.18 / 4.69 (mean 79.8 %, 4.60). With the boxes moved onto their motion evidence (session 35): 84.85 / 76.85 /
// 79.57 %, 4.05 / 4.18 / 4.11 (mean 80.4 %, 4.11; without it 80.3 %, 4.51, which fails the false-alarm bound).
// Session 38's defaults gave 84.89 / 76.85 / 79.64 %, 4.02 / 4.18 / 4.14 (mean 80.5 %, 4.11); with the travel heading
// (session 39) 86.43 / 78.76 / 80.10 %, 3.39 / 3.19 / 3.82 (mean 81.8 %, 3.47): all three bounds fail without it.
// Session 45, features from 5 px inside the border instead of 6 (docs/motion.md, `border_px`): 86.81 / 79.95 / 81.69 %,
// 3.49 / 4.21 / 3.36 -> 86.96 / 80.73 / 82.66 %, 3.85 / 3.78 / 3.93 (mean 82.8 -> 83.5 %, 3.69 -> 3.86): the
// false-alarm bound moved from 3.8 to 3.9. On the held-out seeds 100-109 (250 frames) `lowsnr` stayed at 85.9 % with
// 3.02 -> 3.08 false alarms per frame while six other presets gained (docs/motion.md).
// Issue 18's target (>= 80 %, <= 1 false alarm) is not met yet.
TEST(ChainLowSnrScenario, ThreeSeedsOfLowContrastHoldTheirCorrectRateAndFalseAlarms) {
  SeedFigures f;
  ASSERT_NO_FATAL_FAILURE(score_seeds_1_to_3("lowsnr", f));
  EXPECT_GE(f.correct, 0.81);
  EXPECT_GE(f.worst_correct, 0.775);
  EXPECT_LE(f.false_alarms, 3.9);
}

// `dense` (queues at junctions, cars creeping at 0.05-0.15 px/frame, under the speed floor of frames without 3-D
// structure): with the creep rule (docs/motion.md, `creep_speed_factor`) seeds 1-3, 150 frames, went from 79.64 / 74.49
// / 80.80 % correct, 4.90 / 2.90 / 3.35 false alarms per frame (mean 78.3 %, 3.72) to 85.11 / 78.18 / 84.88 %, 3.97 /
// 3.09 / 3.31 (mean 82.7 %, 3.45). With the boxes moved onto their motion evidence (session 35): 85.06 / 78.59 /
// 85.14 %, 3.53 / 2.67 / 2.96 (mean 82.9 %, 3.05; the false-alarm bound fails without it). Session 38's defaults gave
// 84.93 / 78.70 / 85.02 %, 3.64 / 2.69 / 2.97 (mean 82.9 %, 3.10); with the travel heading (session 39) 85.37 /
// 78.92 / 85.56 %, 3.17 / 2.71 / 2.85 (mean 83.3 %, 2.91; the false-alarm bound fails without it). Issue 18's target
// (>= 80 % on every seed, <= 1 false alarm) is not met yet.
TEST(ChainDenseScenario, ThreeSeedsOfQueuesHoldTheirCorrectRateAndFalseAlarms) {
  SeedFigures f;
  ASSERT_NO_FATAL_FAILURE(score_seeds_1_to_3("dense", f));
  EXPECT_GE(f.correct, 0.82);
  EXPECT_GE(f.worst_correct, 0.78);
  EXPECT_LE(f.false_alarms, 3.0);
}

// `fastcam` (800 x 600, the camera about 21 px per frame: the ground crosses the view in 29 frames). Its misses are
// vehicles in their first frames in view. With one velocity deciding, and one linked feature confirming, only where
// the camera brings new ground in that quickly (docs/tracking.md, session 41: `strong_motion_max_view_frames`,
// `quick_confirm_max_ground_frames`), seeds 1-3 at 150 frames went from 81.93 / 81.00 / 81.53 % correct, 0.83 /
// 0.61 / 0.69 false alarms per frame (mean 81.5 %, 0.71) to 83.85 / 83.78 / 83.79 %, 0.96 / 0.62 / 0.57 (mean
// 83.8 %, 0.72): both correct-rate bounds fail without them. Since session 44 (blob-less clusters placed on their
// motion evidence, the lane rule read along the track's axis) 84.87 / 85.24 / 85.43 %, 1.13 / 0.59 / 0.79 false
// alarms per frame (mean 85.2 %, 0.84): the false-alarm bound is issue 18's target, <= 1 per frame (held-out seeds
// 100-109: 81.48 %, 0.47).
TEST(ChainFastcamScenario, ThreeSeedsOfAFastCameraHoldTheirCorrectRateAndFalseAlarms) {
  SeedFigures f;
  ASSERT_NO_FATAL_FAILURE(score_seeds_1_to_3("fastcam", f, 3000));
  EXPECT_GE(f.correct, 0.84);
  EXPECT_GE(f.worst_correct, 0.84);
  EXPECT_LE(f.false_alarms, 1.0);
}

}  // namespace
}  // namespace uavmot
