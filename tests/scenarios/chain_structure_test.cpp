// The whole chain on a simulated town with 3-D structure (`uavmot sim --preset urban3d`: buildings
// 5-30 m, trees, walls, a camera at 300 m flying 36 m/s): the plane + parallax step must keep roofs,
// walls and trees from becoming tracks without costing moving vehicles. Each seed runs twice, with
// the default configuration and with `motion.parallax_rejection: false`, scored by `uavmot eval`
// (false alarms on static structure from gt/structures.csv).
//
// Figures on 2026-11-25, 100 frames (default / without the parallax step):
//   seed 100: correct 86.88 / 86.69 %, false alarms on structure 12.45 / 51.77 per frame
//   seed 101: correct 87.72 / 87.93 %, false alarms on structure 12.34 / 38.18 per frame
// Issue 17's target (<= 0.1 per frame on structure) is not met yet; docs/motion.md says what is left.

#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <fstream>

#include <nlohmann/json.hpp>

#include "child_process.hpp"

namespace uavmot {
namespace {

using testing::binary;
using testing::ChildProcess;
using testing::fresh_dir;

void run(const std::vector<std::string>& argv, const std::string& log) {
  ChildProcess p(argv, log);
  const auto code = p.wait(std::chrono::minutes(10));
  ASSERT_TRUE(code.has_value()) << argv[1] << " did not finish:\n" << p.log();
  ASSERT_EQ(*code, 0) << p.log();
}

struct Score {
  double correct = 0, on_structure_per_frame = 0;
};

Score score(const std::string& seq, const std::string& out, const std::string& config) {
  std::vector<std::string> process = {binary("uavmot"), "process", seq, "--out", out, "--quiet"};
  if (!config.empty()) process.insert(process.end(), {"--config", config});
  run(process, out + ".process.log");
  run({binary("uavmot"), "eval", "--seq", seq, "--pred", out + "/tracks.txt", "--obb", out + "/tracks_obb.csv", "--json",
       out + "/eval.json"},
      out + ".eval.log");
  std::ifstream in(out + "/eval.json");
  const auto e = nlohmann::json::parse(in);
  return {e.at("completeness").at("correct_rate").get<double>(),
          e.at("false_alarms").at("on_structure_per_frame").get<double>()};
}

TEST(ChainStructureScenario, ParallaxStepKeepsStructureOffTheTracksAndVehiclesOn) {
  const std::string dir = fresh_dir("chain_structure_scenario");
  const std::string no_parallax = dir + "/no_parallax.yaml";
  std::ofstream(no_parallax) << "motion:\n  parallax_rejection: false\n";
  for (const int seed : {100, 101}) {
    const std::string seq = dir + "/urban3d-" + std::to_string(seed);
    run({binary("uavmot"), "sim", "--preset", "urban3d", "--seed", std::to_string(seed), "--frames", "100", "--out", seq,
         "--quiet"},
        seq + ".sim.log");
    const Score with = score(seq, seq + "-out", "");
    const Score without = score(seq, seq + "-out-no-parallax", no_parallax);
    std::printf("urban3d seed %d: correct %.2f / %.2f %%, on structure %.2f / %.2f per frame (default / no parallax step)\n",
                seed, 100 * with.correct, 100 * without.correct, with.on_structure_per_frame, without.on_structure_per_frame);
    EXPECT_LE(with.on_structure_per_frame, 14.0) << "seed " << seed;
    EXPECT_LE(with.on_structure_per_frame, 0.4 * without.on_structure_per_frame) << "seed " << seed;
    EXPECT_GE(with.correct, 0.85) << "seed " << seed;
    EXPECT_GE(with.correct, without.correct - 0.01) << "seed " << seed;
  }
}

}  // namespace
}  // namespace uavmot
