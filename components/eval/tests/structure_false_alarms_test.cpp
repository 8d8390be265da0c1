// False alarms on static structures (buildings, trees, walls): hand-made outlines, the file
// gt/structures.csv, and a simulated urban3d sequence written and read back.
#include <filesystem>
#include <fstream>

#include <unistd.h>

#include <gtest/gtest.h>

#include "eval_test_helpers.hpp"
#include "uavmot/eval/sim_recorder.hpp"
#include "uavmot/sim/sequence_writer.hpp"
#include "uavmot/sim/simulator.hpp"

namespace uavmot::eval {
namespace {
namespace fs = std::filesystem;
using testing::object;
using testing::oriented;

// Frame 1: a moving car, a building (40 x 40 px square) and a tree (a hexagon around (200, 60)).
Sequence town() {
  Sequence s = testing::empty_sequence(2, 0.35);
  s.objects[1] = {object(1, 20, 200, 4, 10)};
  s.has_structures = true;
  s.structures[1] = {{3, "building", {{100, 100}, {140, 100}, {140, 140}, {100, 140}}},
                     {8, "tree", {{210, 60}, {205, 69}, {195, 69}, {190, 60}, {195, 51}, {205, 51}}}};
  return s;
}

TEST(StructureFalseAlarms, BoxesOnABuildingOrTreeCountAsStructureFalseAlarms) {
  Predictions p;
  p.boxes[1] = {oriented(1, 20, 200, 4, 10),    // the car: correct, no false alarm
                oriented(2, 120, 120, 6, 12),   // on the roof: a false alarm on a building
                oriented(3, 139, 120, 6, 12),   // half on the roof's edge (50 %): still on the building
                oriented(4, 200, 60, 8, 8),     // inside the canopy: on a tree
                oriented(5, 250, 200, 6, 12)};  // on open ground: a false alarm, not on a structure
  p.boxes[2] = {oriented(2, 120, 120, 6, 12)};  // frame 2 has no structure truth: plain false alarm
  const EvaluationResult r = evaluate(town(), p);
  EXPECT_EQ(r.completeness.correct, 1);
  EXPECT_EQ(r.false_alarms.false_alarms, 5);
  EXPECT_TRUE(r.false_alarms.structures_known);
  EXPECT_EQ(r.false_alarms.on_structure, 3);
  EXPECT_EQ(r.false_alarms.on_building, 2);
  EXPECT_EQ(r.false_alarms.on_tree, 1);
  EXPECT_EQ(r.false_alarms.on_wall, 0);
  EXPECT_DOUBLE_EQ(r.false_alarms.on_structure_per_frame(), 1.5);
  EXPECT_NE(format_table(r).find("on static structures: 3 (1.500 per frame): 2 on buildings, 1 on trees, 0 on walls"), std::string::npos);
  const auto j = to_json(r);
  EXPECT_EQ(j["false_alarms"]["on_structure"], 3);
  EXPECT_EQ(j["false_alarms"]["on_structure_by_kind"]["tree"], 1);
}

TEST(StructureFalseAlarms, FlatSequencesReportNoStructureCategory) {
  Sequence s = testing::empty_sequence(1);
  Predictions p;
  p.boxes[1] = {oriented(1, 50, 50, 4, 10)};
  const EvaluationResult r = evaluate(s, p);
  EXPECT_FALSE(r.false_alarms.structures_known);
  EXPECT_EQ(format_table(r).find("static structures"), std::string::npos);
  EXPECT_FALSE(to_json(r)["false_alarms"].contains("on_structure"));
}

class StructureFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("uavmot_eval_structures_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "gt");
    std::ofstream(dir_ / "seqinfo.ini") << "[Sequence]\nname=t\nseqLength=2\nimWidth=320\nimHeight=240\ngsd=0.35\n";
    std::ofstream(dir_ / "gt" / "gt_obb.csv") << "frame,id,cx,cy,width,length,angle_deg,moving\n1,1,20,200,4,10,0,1\n";
  }
  void TearDown() override { fs::remove_all(dir_); }
  void structures(const std::string& text) { std::ofstream(dir_ / "gt" / "structures.csv") << text; }
  fs::path dir_;
};

TEST_F(StructureFiles, ReadsOutlinesAndNamesBadLines) {
  const std::string header = "frame,id,kind,height_m,bb_left,bb_top,bb_width,bb_height,outline\n";
  structures(header + "1,3,building,12.0,100,100,40,40,100 100 140 100 140 140 100 140\n");
  const Sequence seq = load_sequence(dir_.string());
  EXPECT_TRUE(seq.has_structures);
  ASSERT_EQ(seq.structures.at(1).size(), 1u);
  EXPECT_EQ(seq.structures.at(1)[0].kind, "building");
  EXPECT_EQ(seq.structures.at(1)[0].outline.size(), 4u);
  const auto error = [&](const std::string& line) {
    structures(header + line);
    try {
      load_sequence(dir_.string());
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(error("1,3,house,12,0,0,1,1,0 0 1 0 1 1\n").find("structures.csv:2"), std::string::npos);
  EXPECT_NE(error("1,3,tree,12,0,0,1,1,0 0 1 0\n").find("three"), std::string::npos);
  EXPECT_NE(error("1,3,tree,12,0,0,1,1,0 0 1 x 1 1\n").find("'x'"), std::string::npos);
  EXPECT_NE(error("5,3,tree,12,0,0,1,1,0 0 1 0 1 1\n").find("outside"), std::string::npos);
}

TEST(StructureFalseAlarms, SimulatedTownWrittenAndRecordedAgree) {
  sim::Scenario s = sim::preset_scenario("urban3d");
  s.frames = 3;
  s.camera.width = 640;
  s.camera.height = 480;
  s.sensor.write_video = false;
  s.traffic.warmup_s = 20.0;
  const std::string out = (fs::temp_directory_path() / ("uavmot_eval_town_" + std::to_string(::getpid()))).string();
  fs::remove_all(out);
  sim::write_sequence(s, 5, out);
  const Sequence from_files = load_sequence(out);
  sim::Simulator simulator(s, 5);
  SimRecorder recorder(simulator);
  sim::SimFrame frame;
  while (simulator.next(frame)) recorder.add(frame);
  const Sequence& recorded = recorder.sequence();
  ASSERT_TRUE(from_files.has_structures);
  ASSERT_TRUE(recorded.has_structures);
  ASSERT_FALSE(recorded.structures.at(1).empty());
  ASSERT_EQ(from_files.structures.at(1).size(), recorded.structures.at(1).size());
  // A box in the middle of every structure is a structure false alarm, in both.
  Predictions p;
  for (const StructureOutline& st : recorded.structures.at(1)) {
    cv::Point2d c(0, 0);
    for (const auto& q : st.outline) c += q;
    c *= 1.0 / static_cast<double>(st.outline.size());
    p.boxes[1].push_back(oriented(-1, c.x, c.y, 2, 2));
  }
  const EvaluationResult a = evaluate(recorded, p), b = evaluate(from_files, p);
  EXPECT_GT(a.false_alarms.on_structure, 0);
  EXPECT_EQ(a.false_alarms.on_structure, b.false_alarms.on_structure);
  EXPECT_EQ(a.false_alarms.on_building, b.false_alarms.on_building);
  fs::remove_all(out);
}

}  // namespace
}  // namespace uavmot::eval
