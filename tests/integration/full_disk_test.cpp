// Results and recordings on a full disk (small tmpfs mounts). `uavmot process`, and `uavmot sink` in a
// launched chain: a 200 KiB tmpfs cannot hold the results of 60 simulated frames; the run must fail
// (exit 1) with an error that names the file and says "No space left on device", and what it wrote
// before must stay valid: complete lines that parse. `uavmot record`: a 4 MiB tmpfs fills mid-run;
// it must fail naming the file, and the recording up to the failure stays readable and recoverable
// (`uavmot record --recover`). Needs root to mount; a machine where the mount is refused fails
// these tests (tools/expected_skips.txt does not apply).

#include <signal.h>
#include <sys/mount.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <sstream>

#include <gtest/gtest.h>

#include "child_process.hpp"
#include "framePubSubTypes.h"
#include "uavmot/build_paths/build_paths.hpp"
#include "uavmot/core/error.hpp"
#include "uavmot/mcap/reader.hpp"
#include "uavmot/dds/cdr_sample.hpp"

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
    const std::string size = std::string("size=") + disk_size();
    ASSERT_EQ(::mount("tmpfs", disk_.c_str(), "tmpfs", 0, size.c_str()), 0)
        << "cannot mount a " << disk_size() << " tmpfs on " << disk_ << ": " << std::strerror(errno)
        << " (this test needs root, or CAP_SYS_ADMIN in its namespace)";
    mounted_ = true;
  }
  void TearDown() override {
    if (mounted_) {
      EXPECT_EQ(::umount2(disk_.c_str(), MNT_DETACH), 0) << std::strerror(errno);
    }
  }
  virtual const char* disk_size() const { return "200k"; }
  // A `paper` sequence of `frames` simulated frames, outside the small disk.
  std::string simulate(int frames) {
    const std::string sequence = root_ + "/seq";
    ChildProcess sim({binary("uavmot-sim"), "--preset", "paper", "--frames", std::to_string(frames), "--out", sequence, "--quiet"},
                     root_ + "/sim.log");
    EXPECT_EQ(sim.wait(std::chrono::seconds(300)), 0) << sim.log();
    return sequence;
  }
  std::string root_, disk_;
  bool mounted_ = false;
};

class FullRecordingDisk : public FullDisk {
 protected:
  const char* disk_size() const override { return "4m"; }
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

void expect_valid_results(const std::string& out) {
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

TEST_F(FullDisk, ProcessFailsNamingTheFileAndKeepsCompleteLines) {
  const std::string sequence = simulate(60);
  ASSERT_FALSE(HasFailure());

  const std::string out = disk_ + "/results";
  ChildProcess process({binary("uavmot-process"), sequence, "--out", out, "--quiet"}, root_ + "/process.log");
  const auto code = process.wait(std::chrono::seconds(300));
  const std::string log = process.log();
  ASSERT_TRUE(code.has_value()) << log;
  EXPECT_EQ(*code, 1) << "a run that could not write its results fails\n" << log;
  EXPECT_NE(log.find("No space left on device"), std::string::npos) << log;
  EXPECT_NE(log.find("'" + out + "/"), std::string::npos) << "the error names the file\n" << log;

  expect_valid_results(out);
}

// The distributed chain's sink (bringup/local.yaml) writing its results onto the full disk: it
// fails, and with it the launch (the sink is required).
TEST_F(FullDisk, SinkFailsNamingTheFileAndKeepsCompleteLines) {
  const std::string sequence = simulate(60);
  ASSERT_FALSE(HasFailure());
  const std::string out = disk_ + "/results";
  ChildProcess launch({binary("uavmot"), "launch", build_paths::source_dir() + "/bringup/local.yaml", "--input",
                       sequence, "--out", out, "--set", "domain=185", "--grace", "20"},
                      root_ + "/launch.log");
  const auto code = launch.wait(std::chrono::seconds(300));
  const std::string log = launch.log();
  ASSERT_TRUE(code.has_value()) << log;
  EXPECT_EQ(*code, 1) << "a launch whose sink could not write its results fails\n" << log;
  EXPECT_NE(log.find("sink exited with code 1"), std::string::npos) << log;
  EXPECT_NE(log.find("No space left on device"), std::string::npos) << log;
  EXPECT_NE(log.find("'" + out + "/"), std::string::npos) << "the error names the file\n" << log;
  expect_valid_results(out);
}

// Frame indices of the recording's uavmot/frames messages up to the first damage, if any.
std::vector<int64_t> recorded_frames(const std::string& file) {
  std::vector<int64_t> indices;
  mcap::Reader reader;
  reader.open(file);
  auto cursor = reader.messages({.topics = {"uavmot/frames"}});
  mcap::MessageView m;
  try {
    while (cursor.next(m)) {
      msg::FramePubSubType type;
      msg::Frame frame;
      dds::from_cdr(type, m.data, m.size, frame, "test");
      indices.push_back(frame.frame_index());
    }
  } catch (const InputError& e) {
    std::printf("%s: reading stopped at the damage: %s\n", file.c_str(), e.what());
  }
  return indices;
}

// 1, 2, ..., n: every frame up to the failure, none missing.
void expect_frames_from_the_first(const std::vector<int64_t>& indices) {
  for (size_t i = 0; i < indices.size(); ++i) ASSERT_EQ(indices[i], static_cast<int64_t>(i + 1)) << "message " << i;
}

TEST_F(FullRecordingDisk, RecordFailsNamingTheFileAndTheRecordingStaysReadable) {
  const std::string sequence = simulate(60);
  ASSERT_FALSE(HasFailure());
  const std::string file = disk_ + "/chain.mcap";
  // Raw frames in small chunks: the disk fills after a few complete chunks.
  ChildProcess record({binary("uavmot-record"), "--out", file, "--topics", "uavmot/frames", "--no-foxglove", "--compression",
                       "none", "--chunk-kb", "512", "--domain", "186"},
                      root_ + "/record.log");
  ChildProcess source({binary("uavmot-source"), sequence, "--domain", "186", "--wait-subscribers", "1"}, root_ + "/source.log");
  const auto code = record.wait(std::chrono::seconds(120));
  source.signal(SIGINT);
  source.wait(std::chrono::seconds(60));
  const std::string log = record.log();
  ASSERT_TRUE(code.has_value()) << "the recorder did not stop on the full disk\n" << log;
  EXPECT_NE(*code, 0) << log;
  EXPECT_NE(log.find("No space left on device"), std::string::npos) << log;
  EXPECT_NE(log.find(file + ".tmp"), std::string::npos) << "the error names the file\n" << log;
  EXPECT_FALSE(fs::exists(file)) << "an unfinished recording is not renamed into place";
  ASSERT_TRUE(fs::exists(file + ".tmp")) << log;

  // Readable as it is, up to the failure...
  const auto as_left = recorded_frames(file + ".tmp");
  ASSERT_FALSE(as_left.empty()) << "no frame readable from the recording";
  expect_frames_from_the_first(as_left);
  // ... and recovered (onto a disk with room) into a complete file with the same frames.
  const std::string recovered = root_ + "/recovered.mcap";
  ChildProcess recover({binary("uavmot-record"), "--recover", file + ".tmp", "--out", recovered}, root_ + "/recover.log");
  ASSERT_EQ(recover.wait(std::chrono::seconds(60)), 0) << recover.log();
  const auto kept = recorded_frames(recovered);
  EXPECT_EQ(kept, as_left);
  std::printf("recorded frames before the disk was full: %zu (of 60)\n", kept.size());
  EXPECT_LT(kept.size(), 60u) << "the disk was not full: the test proves nothing";
}

}  // namespace
}  // namespace uavmot
