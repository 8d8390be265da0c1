// `uavmot process --threads 2` (decode, motion and segmentation + tracking on their own threads)
// writes the same bytes as `--threads 1` (one frame after another), on a simulated flight with
// moving and parked vehicles: the determinism the distributed chain relies on holds when the
// stages overlap. Also with a broken image in the middle: both stop there with the same files
// and the same exit code.

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>

#include "child_process.hpp"

namespace uavmot {
namespace {

using testing::binary;
using testing::ChildProcess;
using testing::fresh_dir;
using testing::read_file;

const char* const kResultFiles[] = {"tracks.txt", "tracks_obb.csv", "homographies.txt", "features.csv", "clusters.txt", "regions.txt"};

int run(const std::vector<std::string>& argv, const std::string& log) {
  ChildProcess p(argv, log);
  const auto code = p.wait(std::chrono::minutes(5));
  EXPECT_TRUE(code.has_value()) << argv[0] << " did not finish:\n" << p.log();
  return code.value_or(-1);
}

int process(const std::string& seq, const std::string& out, int threads) {
  return run({binary("uavmot"), "process", seq, "--out", out, "--quiet", "--threads", std::to_string(threads)}, out + ".log");
}

void expect_same_files(const std::string& a, const std::string& b) {
  for (const char* name : kResultFiles) {
    const std::string one = read_file(a + "/" + name), two = read_file(b + "/" + name);
    EXPECT_FALSE(one.empty()) << name;
    EXPECT_TRUE(one == two) << name << " differs between --threads 1 and --threads 2 (" << one.size() << " vs "
                            << two.size() << " bytes)";
  }
}

class PipelinedChain : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = fresh_dir("pipelined_chain_scenario");
    seq_ = dir_ + "/paper";
    ASSERT_EQ(run({binary("uavmot"), "sim", "--preset", "paper", "--seed", "2", "--frames", "80", "--out", seq_, "--quiet"},
                  dir_ + "/sim.log"),
              0);
  }
  static std::string dir_, seq_;
};
std::string PipelinedChain::dir_, PipelinedChain::seq_;

TEST_F(PipelinedChain, WritesTheSameBytesAsTheSequentialRun) {
  ASSERT_EQ(process(seq_, dir_ + "/t1", 1), 0);
  ASSERT_EQ(process(seq_, dir_ + "/t2", 2), 0);
  expect_same_files(dir_ + "/t1", dir_ + "/t2");
  // Confirmed tracks exist: the comparison is about real content, not two empty files.
  EXPECT_GT(read_file(dir_ + "/t1/tracks.txt").size(), 1000u);
}

TEST_F(PipelinedChain, BrokenImageStopsBothModesAtTheSameFrame) {
  // A copy of the sequence whose 40th image is not an image.
  const std::string broken = dir_ + "/broken";
  std::filesystem::copy(seq_, broken, std::filesystem::copy_options::recursive);
  std::ofstream(broken + "/img1/000040.jpg", std::ios::trunc) << "not a jpeg";
  EXPECT_EQ(process(broken, dir_ + "/b1", 1), 2);
  EXPECT_EQ(process(broken, dir_ + "/b2", 2), 2);
  expect_same_files(dir_ + "/b1", dir_ + "/b2");
  EXPECT_NE(read_file(dir_ + "/b2.log").find("000040.jpg"), std::string::npos) << read_file(dir_ + "/b2.log");
}

}  // namespace
}  // namespace uavmot
