// The distributed chain started by `uavmot launch bringup/local.yaml`: real processes over Fast DDS.

#include <signal.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <thread>

#include <gtest/gtest.h>
#include <opencv2/videoio.hpp>

#include "child_process.hpp"
#include "uavmot/build_paths/build_paths.hpp"
#include "uavmot/mcap/reader.hpp"

namespace uavmot {
namespace {
using testing::binary;
using testing::ChildProcess;
using testing::read_file;
namespace fs = std::filesystem;

const std::string kProfile = build_paths::source_dir() + "/bringup/local.yaml";

class ChainLaunch : public ::testing::Test {
 protected:
  // One short simulated sequence and its in-process result, shared by the tests.
  static void SetUpTestSuite() {
    root_ = testing::fresh_dir("chain_launch");
    sequence_ = root_ + "/paper";
    ChildProcess sim({binary("uavmot-sim"), "--preset", "paper", "--seed", "7", "--frames", "120", "--out", sequence_},
                     root_ + "/sim.log");
    ASSERT_EQ(sim.wait(std::chrono::seconds(120)), 0) << sim.log();
    ChildProcess process({binary("uavmot-process"), sequence_, "--out", root_ + "/process", "--quiet"}, root_ + "/process.log");
    ASSERT_EQ(process.wait(std::chrono::seconds(240)), 0) << process.log();
  }

  static std::string root_, sequence_;
};
std::string ChainLaunch::root_, ChainLaunch::sequence_;

int last_frame_in(const std::string& mot_file) {
  std::ifstream in(mot_file);
  int last = 0;
  for (std::string line; std::getline(in, line);) last = std::max(last, std::stoi(line.substr(0, line.find(','))));
  return last;
}

TEST_F(ChainLaunch, LosslessTracksAreByteIdenticalToInProcess) {
  const std::string out = root_ + "/launch_identical";
  ChildProcess launch({binary("uavmot"), "launch", kProfile, "--input", sequence_, "--out", out, "--set", "domain=31"},
                      root_ + "/launch_identical.log");
  ASSERT_EQ(launch.wait(std::chrono::seconds(240)), 0) << launch.log();
  const std::string expected = read_file(root_ + "/process/tracks.txt");
  ASSERT_FALSE(expected.empty()) << "the in-process run found no tracks: nothing would be compared";
  EXPECT_EQ(read_file(out + "/tracks.txt"), expected);
  for (const char* file : {"tracks_obb.csv", "homographies.txt", "features.csv", "clusters.txt", "regions.txt"}) {
    EXPECT_EQ(read_file(out + "/" + file), read_file(root_ + "/process/" + file)) << file;
  }
  // Every line a process printed carries its name.
  EXPECT_NE(launch.log().find("[motion"), std::string::npos);
  EXPECT_NE(launch.log().find("[sink"), std::string::npos);
}

// With flight metadata: the sequence as H.264 muxed with aphill_short.ts's KLV stream. The sink reads
// the metadata itself (`--set metadata=FILE`, uavmot sink --metadata) and writes the same
// tracks.geojson and lat,lon columns as the in-process run, byte for byte.
TEST_F(ChainLaunch, SinkWithMetadataWritesTheSameTracksGeojsonAsProcess) {
  const std::string ts = root_ + "/klv.ts";
  ChildProcess mux({"/usr/bin/ffmpeg", "-nostdin", "-v", "error", "-y", "-framerate", "25", "-i", sequence_ + "/img1/%06d.jpg", "-i",
                    build_paths::data_dir() + "/aphill/aphill_short.ts", "-map", "0:v", "-map", "1:d", "-c:v", "libx264",
                    "-preset", "veryfast", "-pix_fmt", "yuv420p", "-c:d", "copy", "-f", "mpegts", ts},
                   root_ + "/mux.log");
  ASSERT_EQ(mux.wait(std::chrono::seconds(120)), 0) << mux.log();
  // The launcher's GSD for an input without seqinfo.ini is 0.35; the same here, so only the map differs from usual.
  ChildProcess process({binary("uavmot-process"), ts, "--out", root_ + "/klv_process", "--gsd", "0.35", "--quiet"},
                       root_ + "/klv_process.log");
  ASSERT_EQ(process.wait(std::chrono::seconds(240)), 0) << process.log();
  const std::string out = root_ + "/klv_launch";
  ChildProcess launch({binary("uavmot"), "launch", kProfile, "--input", ts, "--out", out, "--set", "domain=37", "--set", "metadata=" + ts},
                      root_ + "/klv_launch.log");
  ASSERT_EQ(launch.wait(std::chrono::seconds(240)), 0) << launch.log();
  const std::string expected = read_file(root_ + "/klv_process/tracks.geojson");
  ASSERT_NE(expected.find("LineString"), std::string::npos) << "no track on the map: nothing would be compared";
  EXPECT_EQ(read_file(out + "/tracks.geojson"), expected);
  for (const char* file : {"tracks.txt", "tracks_obb.csv"}) {
    EXPECT_EQ(read_file(out + "/" + file), read_file(root_ + "/klv_process/" + file)) << file;
  }
  EXPECT_NE(read_file(out + "/tracks_obb.csv").find(",lat,lon\n"), std::string::npos);
}

// `--set view=true --set record=true` adds the viewer and the recorder, and every writer of a
// lossless chain counts them (${readers:TOPIC}): the video has every frame, the recording every
// sample, and the chain's results stay identical to the in-process run.
TEST_F(ChainLaunch, ViewerAndRecorderInTheProfileAreWaitedForAndGetEverything) {
  const std::string out = root_ + "/launch_observed";
  ChildProcess launch({binary("uavmot"), "launch", kProfile, "--input", sequence_, "--out", out, "--set", "domain=143",
                       "--set", "view=true", "--set", "record=true"},
                      root_ + "/launch_observed.log");
  ASSERT_EQ(launch.wait(std::chrono::seconds(400)), 0) << launch.log();
  const std::string log = launch.log();
  // Two more readers of frames, motion, segmentation and tracks than the plain chain has.
  for (const auto& [name, readers] : std::map<std::string, int>{{"source", 4}, {"motion", 5}, {"segmentation", 4}, {"tracking", 3}}) {
    const std::regex started("started " + name + R"( \(pid \d+\): uavmot-)" + name + "[^\n]* --wait-subscribers " +
                             std::to_string(readers) + " ");
    EXPECT_TRUE(std::regex_search(log, started)) << name << " should wait for " << readers << " readers:\n" << log;
  }
  EXPECT_EQ(read_file(out + "/tracks.txt"), read_file(root_ + "/process/tracks.txt"));

  mcap::Reader recording;
  recording.open(out + "/chain.mcap");
  EXPECT_FALSE(recording.damage().has_value());
  std::map<std::string, uint64_t> count;
  for (const auto& [id, channel] : recording.channels()) {
    const auto n = recording.statistics().channel_message_counts.find(id);
    count[channel.topic] = n == recording.statistics().channel_message_counts.end() ? 0 : n->second;
  }
  // 120 frames and results plus each topic's end-of-stream sample.
  for (const char* topic : {"uavmot/frames", "uavmot/motion", "uavmot/segmentation", "uavmot/tracks"}) {
    EXPECT_EQ(count[topic], 121u) << topic;
  }

  cv::VideoCapture video(out + "/annotated.mp4");
  ASSERT_TRUE(video.isOpened());
  int frames = 0;
  for (cv::Mat image; video.read(image);) ++frames;
  EXPECT_EQ(frames, 120);
  EXPECT_EQ(log.find("drawn before their tracks arrived"), std::string::npos) << "every frame drawn with its tracks:\n" << log;
}

TEST_F(ChainLaunch, KilledComponentIsRespawnedAndTheChainGoesOn) {
  const std::string out = root_ + "/launch_kill";
  // Slow the source so the kill lands mid-sequence.
  ChildProcess launch({binary("uavmot"), "launch", kProfile, "--input", sequence_, "--out", out, "--set", "domain=32"},
                      root_ + "/launch_kill.log");
  // Wait until tracking runs and some tracks were written, then SIGKILL it.
  pid_t tracking = -1;
  const std::regex started(R"(started tracking \(pid (\d+)\))");
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (std::chrono::steady_clock::now() < deadline) {
    std::smatch m;
    const std::string log = launch.log();
    if (tracking < 0 && std::regex_search(log, m, started)) tracking = std::stoi(m[1]);
    if (tracking > 0 && log.find("published 20 frames") != std::string::npos) break;
    if (tracking > 0 && fs::exists(out + "/tracks_obb.csv") && fs::file_size(out + "/tracks_obb.csv") > 2000) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ASSERT_GT(tracking, 0) << launch.log();
  ASSERT_EQ(::kill(tracking, SIGKILL), 0);
  ASSERT_EQ(launch.wait(std::chrono::seconds(240)), 0) << launch.log();
  const std::string log = launch.log();
  EXPECT_NE(log.find("tracking killed by signal 9"), std::string::npos) << log;
  EXPECT_NE(log.find("respawning in 1.0 s (1/3)"), std::string::npos) << log;
  EXPECT_GE(std::count(log.begin(), log.end(), '\n'), 10);
  // The chain went on to the end of the sequence: every frame's motion and the last frames' tracks were written.
  EXPECT_EQ(last_frame_in(out + "/homographies.txt"), 120);
  EXPECT_GE(last_frame_in(out + "/tracks.txt"), 110);
}

TEST_F(ChainLaunch, FailingRequiredProcessEndsTheLaunchWithAClearMessage) {
  ChildProcess launch({binary("uavmot"), "launch", kProfile, "--input", sequence_, "--out", "/proc/uavmot-cannot-write",
                       "--set", "domain=33", "--grace", "3"},
                      root_ + "/launch_fail.log");
  const auto code = launch.wait(std::chrono::seconds(120));
  ASSERT_TRUE(code.has_value()) << launch.log();
  EXPECT_NE(*code, 0);
  EXPECT_NE(launch.log().find("required process sink failed"), std::string::npos) << launch.log();
}

TEST_F(ChainLaunch, ProfileTypoIsNamedWithItsLine) {
  const std::string profile = root_ + "/typo.yaml";
  std::ofstream(profile) << "processes:\n  - name: sink\n    comand: sink\n";
  ChildProcess launch({binary("uavmot"), "launch", profile, "--out", root_ + "/typo"}, root_ + "/launch_typo.log");
  EXPECT_EQ(launch.wait(std::chrono::seconds(20)), 2);
  EXPECT_NE(launch.log().find("typo.yaml:3"), std::string::npos) << launch.log();
  EXPECT_NE(launch.log().find("did you mean 'command'"), std::string::npos) << launch.log();
}

}  // namespace
}  // namespace uavmot
