// The uavmot-eval process: table on stdout, JSON file, and clear failures on bad input.
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <unistd.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "uavmot/sim/sequence_writer.hpp"

namespace {
namespace fs = std::filesystem;

struct ProcessResult {
  int code = -1;
  std::string output;
};

ProcessResult run_eval(const std::string& args) {
  const fs::path log = fs::temp_directory_path() / ("uavmot_eval_cli_" + std::to_string(::getpid()) + ".log");
  const std::string cmd = std::string(UAVMOT_BINARY_DIR) + "/bin/uavmot-eval " + args + " >" + log.string() + " 2>&1";
  const int status = std::system(cmd.c_str());
  ProcessResult r;
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream in(log);
  std::stringstream ss;
  ss << in.rdbuf();
  r.output = ss.str();
  fs::remove(log);
  return r;
}

class EvalCli : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = fs::temp_directory_path() / ("uavmot_eval_cli_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    uavmot::sim::Scenario s = uavmot::sim::preset_scenario("paper");
    s.frames = 3;
    s.camera.width = 320;
    s.camera.height = 240;
    s.sensor.write_video = false;
    uavmot::sim::write_sequence(s, 2, (dir_ / "seq").string());
  }
  static void TearDownTestSuite() { fs::remove_all(dir_); }
  static std::string write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name) << text;
    return (dir_ / name).string();
  }
  static std::string seq() { return (dir_ / "seq").string(); }
  static fs::path dir_;
};
fs::path EvalCli::dir_;

TEST_F(EvalCli, ScoresTheTruthAsPerfectAndWritesJson) {
  const std::string json = (dir_ / "out.json").string();
  const ProcessResult r = run_eval("--seq " + seq() + " --pred " + seq() + "/gt/gt.txt --homographies " + seq() +
                                   "/gt/homographies.txt --json " + json);
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("Completeness (paper Table I)"), std::string::npos);
  EXPECT_NE(r.output.find("MOTA"), std::string::npos);
  std::ifstream in(json);
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_DOUBLE_EQ(j["tracking"][0]["MOTA"].get<double>(), 1.0);
  EXPECT_DOUBLE_EQ(j["tracking"][0]["IDF1"].get<double>(), 1.0);
  EXPECT_DOUBLE_EQ(j["homography"]["max_px"].get<double>(), 0.0);
  EXPECT_EQ(j["false_alarms"]["false_alarms"].get<int>(), 0);
  EXPECT_GT(j["completeness"]["instances"].get<int>(), 0);
}

TEST_F(EvalCli, HelpAndDescribe) {
  EXPECT_EQ(run_eval("--help").code, 0);
  const ProcessResult d = run_eval("--describe");
  EXPECT_EQ(d.code, 0);
  EXPECT_EQ(std::count(d.output.begin(), d.output.end(), '\n'), 1);
}

TEST_F(EvalCli, BadInputFailsClearly) {
  ProcessResult r = run_eval("--seq " + seq() + " --pred " + write("bad.txt", "1,1,x,2,3,4,1,-1,-1,-1\n"));
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.output.find("bad.txt:1"), std::string::npos) << r.output;

  r = run_eval("--seq " + seq() + " --pred " + write("late.txt", "99,1,1,2,3,4,1,-1,-1,-1\n"));
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.output.find("outside the sequence"), std::string::npos) << r.output;

  r = run_eval("--seq " + seq() + " --pred " + (dir_ / "absent.txt").string());
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.output.find("absent.txt"), std::string::npos) << r.output;

  r = run_eval("--seq " + (dir_ / "noseq").string() + " --pred " + seq() + "/gt/gt.txt");
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.output.find("noseq"), std::string::npos) << r.output;

  r = run_eval("--seq " + seq());
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.output.find("--pred"), std::string::npos) << r.output;

  r = run_eval("--seq " + seq() + " --pred " + seq() + "/gt/gt.txt --features " + write("f.csv", "frame,feature_id,x,y,vx,vy,moving\n1,1,2,3,0,0,maybe\n"));
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.output.find("f.csv:2"), std::string::npos) << r.output;
}

}  // namespace
