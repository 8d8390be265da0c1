// The ground sink's faults, with UAVs played by participants of this test on the downlink topic.
// - A UAV vanishes mid-run (its participant is gone without an end of stream, as after a crash or a
//   lost link). With --stream-timeout the sink gives that stream up after the timeout, keeps writing
//   the other one, ends with the other's end of stream, exits 1 to say a stream was lost, and both
//   folders keep everything that arrived.
// - The sink itself is SIGKILLed mid-run and started again with --resume: the UAV's writer sends its
//   history again (transient-local), the sink skips what its files hold, and the files end equal
//   to those of a sink that was never killed.

#include <algorithm>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <optional>
#include <thread>

#include <gtest/gtest.h>

#include "child_process.hpp"
#include "downlinkPubSubTypes.h"
#include "uavmot/dds/downlink_convert.hpp"
#include "uavmot/dds/participant.hpp"

namespace uavmot {
namespace {
namespace fs = std::filesystem;
using testing::binary;
using testing::ChildProcess;
constexpr int kDomain = 79;

// One UAV's side of the link: its own participant and results writer.
class Uav {
 public:
  explicit Uav(std::string stream) : stream_(std::move(stream)) {
    dds::DdsOptions o;
    o.domain_id = kDomain;
    o.participant_name = "air_" + stream_;
    participant_.emplace(o);
    writer_ = participant_->make_writer<msg::FrameResultsPubSubType>(dds::kDownlinkResultsTopic, dds::TopicClass::Downlink);
  }
  bool matched(size_t readers = 1) { return writer_->wait_for_matched(readers, std::chrono::seconds(30)); }
  bool send(int64_t k) {
    dds::FrameParts parts;
    parts.motion.emplace();
    parts.motion->stream_id = stream_;
    parts.motion->frame_index = k;
    parts.motion->image_width = 640;
    parts.motion->image_height = 480;
    TrackList t;
    t.stream_id = stream_;
    t.frame_index = k;
    Track track;
    track.id = 7;
    track.state = TrackState::Confirmed;
    track.box = {100.0 + static_cast<double>(k), 50, 2, 10, 0};
    t.tracks = {track};
    parts.tracks = t;
    auto sample = dds::to_downlink_msg(stream_, k, parts);
    return writer_->write_reliably(sample);
  }
  bool end(int64_t k) {
    msg::FrameResults eos;
    eos.stream_id(stream_);
    eos.frame_index(k);
    eos.end_of_stream(true);
    return writer_->write_reliably(eos);
  }
  // Every sample sent is delivered (write_reliably waits for the previous one's acknowledgement only).
  bool delivered() { return writer_->flush(); }
  // Gone at once, as a UAV that lost power: no end of stream, no goodbye.
  void vanish() {
    writer_.reset();
    participant_.reset();
  }

 private:
  std::string stream_;
  std::optional<dds::Participant> participant_;
  std::unique_ptr<dds::TopicWriter<msg::FrameResultsPubSubType>> writer_;
};

int64_t lines(const fs::path& file) {
  const std::string text = testing::read_file(file.string());
  return std::count(text.begin(), text.end(), '\n');
}

TEST(SinkLostStream, UavThatVanishesIsGivenUpAndTheOtherStreamEndsTheRun) {
  const std::string root = testing::fresh_dir("sink_lost_stream");
  const fs::path out = fs::path(root) / "results";
  ChildProcess sink({binary("uavmot-sink"), "--downlink", "--streams", "2", "--stream-timeout", "1.5", "--out", out.string(),
                     "--domain", std::to_string(kDomain), "--mode", "lossless"},
                    root + "/sink.log");
  Uav uav1("uav1"), uav2("uav2");
  ASSERT_TRUE(uav1.matched());
  ASSERT_TRUE(uav2.matched());
  for (int k = 1; k <= 4; ++k) {
    ASSERT_TRUE(uav1.send(k));
    ASSERT_TRUE(uav2.send(k));
  }
  ASSERT_TRUE(uav2.delivered());
  uav2.vanish();
  // uav1 goes on for 3 s, twice the timeout: the sink must neither stop nor drop its frames.
  for (int k = 5; k <= 16; ++k) {
    std::this_thread::sleep_for(std::chrono::milliseconds(250));
    ASSERT_TRUE(uav1.send(k));
  }
  EXPECT_FALSE(sink.wait(std::chrono::milliseconds(200)).has_value()) << "uav1 has not ended\n" << sink.log();
  ASSERT_TRUE(uav1.end(16));
  EXPECT_EQ(sink.wait(std::chrono::seconds(30)), 1) << "a lost stream is a failed run\n" << sink.log();

  EXPECT_EQ(lines(out / "uav1/tracks.txt"), 16);
  EXPECT_EQ(lines(out / "uav1/homographies.txt"), 16);
  EXPECT_EQ(lines(out / "uav2/tracks.txt"), 4) << "what arrived of the lost stream is kept";
  EXPECT_TRUE(fs::exists(out / "uav1/summary.json"));
  EXPECT_TRUE(fs::exists(out / "uav2/summary.json"));
  const std::string log = sink.log();
  EXPECT_NE(log.find("stream 'uav2': nothing for 1.5 s after frame 4: given up as lost"), std::string::npos) << log;
  EXPECT_EQ(log.find("stream 'uav1': nothing for"), std::string::npos) << log;
  EXPECT_NE(log.find("1 stream(s) lost before their end of stream"), std::string::npos) << log;
}

// Without --stream-timeout (the default) nothing is given up: the sink still waits for uav2.
TEST(SinkLostStream, WithoutTimeoutTheSinkWaitsForEveryStream) {
  const std::string root = testing::fresh_dir("sink_lost_stream_wait");
  const fs::path out = fs::path(root) / "results";
  ChildProcess sink({binary("uavmot-sink"), "--downlink", "--streams", "2", "--out", out.string(), "--domain",
                     std::to_string(kDomain), "--mode", "lossless"},
                    root + "/sink.log");
  Uav uav1("uav1"), uav2("uav2");
  ASSERT_TRUE(uav1.matched());
  ASSERT_TRUE(uav2.matched());
  ASSERT_TRUE(uav1.send(1));
  ASSERT_TRUE(uav2.send(1));
  uav2.vanish();
  ASSERT_TRUE(uav1.end(1));
  EXPECT_FALSE(sink.wait(std::chrono::seconds(3)).has_value()) << sink.log();
  sink.signal(SIGTERM);
  EXPECT_TRUE(sink.wait(std::chrono::seconds(20)).has_value()) << sink.log();
}

std::vector<std::string> kResultFiles = {"tracks.txt", "tracks_obb.csv", "homographies.txt", "regions.txt"};

TEST(SinkRestart, KilledSinkContinuedWithResumeEndsWithTheFilesOfAnUninterruptedRun) {
  const std::string root = testing::fresh_dir("sink_restart");
  const fs::path killed = fs::path(root) / "killed", whole = fs::path(root) / "whole";
  auto sink_args = [&](const fs::path& out, bool resume) {
    std::vector<std::string> args = {binary("uavmot-sink"), "--downlink", "--out", out.string(), "--domain",
                                     std::to_string(kDomain), "--mode", "lossless", "--stream-id", "uav1"};
    if (resume) args.push_back("--resume");
    return args;
  };
  // Two sinks: one is killed and restarted, the other runs undisturbed beside it.
  ChildProcess undisturbed(sink_args(whole, false), root + "/whole.log");
  std::optional<ChildProcess> sink;
  sink.emplace(sink_args(killed, false), root + "/killed.log");
  Uav uav("uav1");
  ASSERT_TRUE(uav.matched(2));
  for (int k = 1; k <= 6; ++k) ASSERT_TRUE(uav.send(k));  // acknowledged by both sinks
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (lines(killed / "homographies.txt") < 6 && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ASSERT_EQ(lines(killed / "homographies.txt"), 6) << sink->log();
  sink->signal(SIGKILL);
  ASSERT_EQ(sink->wait(std::chrono::seconds(10)), 128 + SIGKILL);
  EXPECT_FALSE(fs::exists(killed / "summary.json"));
  sink.emplace(sink_args(killed, true), root + "/resumed.log");
  ASSERT_TRUE(uav.matched(2));
  for (int k = 7; k <= 12; ++k) ASSERT_TRUE(uav.send(k));
  ASSERT_TRUE(uav.end(12));
  ASSERT_EQ(undisturbed.wait(std::chrono::seconds(30)), 0) << undisturbed.log();
  ASSERT_EQ(sink->wait(std::chrono::seconds(30)), 0) << sink->log();

  EXPECT_EQ(lines(whole / "homographies.txt"), 12);
  for (const auto& name : kResultFiles) {
    EXPECT_EQ(testing::read_file((killed / name).string()), testing::read_file((whole / name).string())) << name;
  }
  EXPECT_NE(sink->log().find("continuing the run in"), std::string::npos) << sink->log();
  EXPECT_NE(testing::read_file((killed / "summary.json").string()).find("\"frames\": 12"), std::string::npos);
}

// --resume never continues a finished run: exit 2 and the files stay as they were.
TEST(SinkRestart, FinishedRunIsNotContinued) {
  const std::string root = testing::fresh_dir("sink_restart_finished");
  const fs::path out = fs::path(root) / "results";
  fs::create_directories(out);
  std::ofstream(out / "summary.json") << "{}\n";
  std::ofstream(out / "homographies.txt") << "1,1,0,0,0,1,0,0,0,1\n";
  ChildProcess sink({binary("uavmot-sink"), "--downlink", "--out", out.string(), "--domain", std::to_string(kDomain), "--resume",
                     "--stream-id", "uav1"},
                    root + "/sink.log");
  Uav uav("uav1");
  ASSERT_TRUE(uav.matched());
  ASSERT_TRUE(uav.send(1));
  EXPECT_EQ(sink.wait(std::chrono::seconds(30)), 2) << sink.log();
  EXPECT_NE(sink.log().find("has ended (summary.json)"), std::string::npos) << sink.log();
  EXPECT_EQ(testing::read_file((out / "homographies.txt").string()), "1,1,0,0,0,1,0,0,0,1\n");
}

}  // namespace
}  // namespace uavmot
