// The whole chain as a user runs it: `uavmot sim --preset paper --seed 1`, `uavmot process` with
// the default configuration, scored by `uavmot eval` (paper Tables I/II, TrackEval). Issue 6's
// targets are asserted as it states them: 95 % correct (95.2 % on this seed), no under- or
// over-segmentation, position within 1.5 px, width 2 px, length 3 px, nothing on a parked car.
// False alarms and MOTA are held at the level reached (docs/tracking.md, "End to end on every
// preset"), with a small margin, so a change that costs accuracy fails here.

#include <gtest/gtest.h>

#include <chrono>
#include <fstream>

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

TEST(ChainPaperScenario, TracksMeetThePrecisionTargetsAndStayOffParkedCars) {
  const std::string dir = fresh_dir("chain_paper_scenario");
  const std::string seq = dir + "/paper", out = dir + "/out";
  ASSERT_EQ(run({binary("uavmot"), "sim", "--preset", "paper", "--seed", "1", "--out", seq, "--quiet"}, dir + "/sim.log"), 0);
  ASSERT_EQ(run({binary("uavmot"), "process", seq, "--out", out, "--quiet"}, dir + "/process.log"), 0);
  ASSERT_EQ(run({binary("uavmot"), "eval", "--seq", seq, "--pred", out + "/tracks.txt", "--obb", out + "/tracks_obb.csv",
                 "--json", out + "/eval.json"},
                dir + "/eval.log"),
            0);
  std::ifstream in(out + "/eval.json");
  const auto e = nlohmann::json::parse(in);
  const auto& c = e.at("completeness");
  const auto& p = e.at("precision");
  const auto& f = e.at("false_alarms");
  ASSERT_GT(c.at("instances").get<int>(), 10000);
  EXPECT_GE(c.at("correct_rate").get<double>(), 0.95);
  EXPECT_EQ(c.at("under_segmented").get<int>(), 0);
  EXPECT_EQ(c.at("over_segmented").get<int>(), 0);
  EXPECT_LE(p.at("error_x_px").get<double>(), 1.5);
  EXPECT_LE(p.at("error_y_px").get<double>(), 1.5);
  EXPECT_LE(p.at("error_width_px").get<double>(), 2.0);
  EXPECT_LE(p.at("error_length_px").get<double>(), 3.0);
  EXPECT_EQ(f.at("on_parked").get<int>(), 0);
  EXPECT_LE(f.at("per_frame").get<double>(), 3.0);
  for (const auto& t : e.at("tracking")) {
    if (t.at("iou_threshold").get<double>() < 0.4) {
      EXPECT_GE(t.at("MOTA").get<double>(), 0.905);  // IoU 0.3, the small-object threshold
    }
  }
}

}  // namespace
}  // namespace uavmot
