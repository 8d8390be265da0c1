// `uavmot process` on a full disk: a 200 KiB tmpfs cannot hold the results of 60 simulated frames.
// The run must fail (exit 1) with an error that names the file and says "No space left on device",
// and what it wrote before must stay valid: complete lines that parse. Needs root to mount; a
// machine where the mount is refused fails this test (tools/expected_skips.txt does not apply).

#include <sys/mount.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <sstream>

#include <gtest/gtest.h>

#include "child_process.hpp"

namespace uavmot {
namespace {
namespace fs = std::filesystem;
using testing::binary;
using testing::ChildProcess;

class FullDisk : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = testing::fresh_dir("full_disk");
    disk_ = root_ + "/disk";
    fs::create_directories(disk_);
    ASSERT_EQ(::mount("tmpfs", disk_.c_str(), "tmpfs", 0, "size=200k"), 0)
        << "cannot mount a 200 KiB tmpfs on " << disk_ << ": " << std::strerror(errno)
        << " (this test needs root, or CAP_SYS_ADMIN in its namespace)";
    mounted_ = true;
  }
  void TearDown() override {
    if (mounted_) {
      EXPECT_EQ(::umount2(disk_.c_str(), MNT_DETACH), 0) << std::strerror(errno);
    }
  }
  std::string root_, disk_;
  bool mounted_ = false;
};

// Every line of a MOTChallenge file: ten comma-separated numbers, ending in a newline.
void expect_complete_mot_lines(const std::string& path) {
  const std::string text = testing::read_file(path);
  ASSERT_TRUE(text.empty() || text.back() == '\n') << path << " ends in a partial line";
  std::istringstream lines(text);
  std::string line;
  int n = 0;
  while (std::getline(lines, line)) {
    ++n;
    std::istringstream fields(line);
    std::string field;
    int count = 0;
    while (std::getline(fields, field, ',')) {
      size_t used = 0;
      EXPECT_NO_THROW((void)std::stod(field, &used)) << path << ":" << n << ": " << line;
      EXPECT_EQ(used, field.size()) << path << ":" << n << ": " << line;
      ++count;
    }
    EXPECT_EQ(count, 10) << path << ":" << n << ": " << line;
  }
}

TEST_F(FullDisk, ProcessFailsNamingTheFileAndKeepsCompleteLines) {
  const std::string sequence = root_ + "/seq";
  ChildProcess sim({binary("uavmot-sim"), "--preset", "paper", "--frames", "60", "--out", sequence, "--quiet"}, root_ + "/sim.log");
  ASSERT_EQ(sim.wait(std::chrono::seconds(300)), 0) << sim.log();

  const std::string out = disk_ + "/results";
  ChildProcess process({binary("uavmot-process"), sequence, "--out", out, "--quiet"}, root_ + "/process.log");
  const auto code = process.wait(std::chrono::seconds(300));
  const std::string log = process.log();
  ASSERT_TRUE(code.has_value()) << log;
  EXPECT_EQ(*code, 1) << "a run that could not write its results fails\n" << log;
  EXPECT_NE(log.find("No space left on device"), std::string::npos) << log;
  EXPECT_NE(log.find("'" + out + "/"), std::string::npos) << "the error names the file\n" << log;

  for (const char* name : {"tracks.txt", "regions.txt", "clusters.txt"}) {
    SCOPED_TRACE(name);
    expect_complete_mot_lines(out + "/" + name);
  }
  for (const char* name : {"tracks_obb.csv", "homographies.txt", "features.csv"}) {
    const std::string text = testing::read_file(out + "/" + name);
    EXPECT_TRUE(text.empty() || text.back() == '\n') << name << " ends in a partial line";
  }
  EXPECT_FALSE(fs::exists(out + "/summary.json")) << "no summary of a run that failed";
}

}  // namespace
}  // namespace uavmot
