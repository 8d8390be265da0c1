// The uavmot-eval process: table on stdout, JSON file, and clear failures on bad input.
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include <unistd.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "motionPubSubTypes.h"
#include "tracksPubSubTypes.h"
#include "uavmot/build_paths/build_paths.hpp"
#include "uavmot/dds/chain_convert.hpp"
#include "uavmot/mcap/writer.hpp"
#include "uavmot/dds/cdr_sample.hpp"
#include "uavmot/sim/sequence_writer.hpp"

namespace {
namespace fs = std::filesystem;

struct ProcessResult {
  int code = -1;
  std::string output;
};

ProcessResult run_eval(const std::string& args) {
  const fs::path log = fs::temp_directory_path() / ("uavmot_eval_cli_" + std::to_string(::getpid()) + ".log");
  const std::string cmd = uavmot::build_paths::binary_dir() + "/bin/uavmot-eval " + args + " >" + log.string() + " 2>&1";
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

// A recording as `uavmot record` writes it (CDR on uavmot/tracks and uavmot/motion), here of the
// ground truth itself, one track list and one motion estimate per frame of stream `stream`.
void write_truth_recording(const std::string& seq, const std::string& path, const std::vector<std::string>& streams,
                           bool with_tracks = true) {
  std::map<int64_t, uavmot::TrackList> lists;
  std::ifstream gt(seq + "/gt/gt.txt");
  for (std::string line; std::getline(gt, line);) {
    std::vector<double> v;
    std::stringstream row(line);
    for (std::string cell; std::getline(row, cell, ',');) v.push_back(std::stod(cell));
    uavmot::Track t;
    t.id = static_cast<uint64_t>(v[1]);
    t.state = uavmot::TrackState::Confirmed;
    t.box = {v[2] + v[4] / 2, v[3] + v[5] / 2, v[5], v[4], 0.0};  // cx, cy, width across, length along x
    lists[static_cast<int64_t>(v[0])].tracks.push_back(t);
  }
  std::map<int64_t, uavmot::Homography> homographies;
  std::ifstream h(seq + "/gt/homographies.txt");
  for (std::string line; std::getline(h, line);) {
    std::vector<double> v;
    std::stringstream row(line);
    for (std::string cell; std::getline(row, cell, ',');) v.push_back(std::stod(cell));
    uavmot::Homography m;
    for (int i = 0; i < 9; ++i) m.val[i] = v[static_cast<size_t>(i + 1)];
    homographies[static_cast<int64_t>(v[0])] = m;
  }
  uavmot::mcap::Writer writer;
  writer.open(path);
  const uint16_t tracks_channel =
      with_tracks ? writer.add_channel(writer.add_schema("uavmot::msg::TrackList", "omgidl", "struct TrackList {};"),
                                       "uavmot/tracks", "cdr", {})
                  : 0;
  const uint16_t motion_channel = writer.add_channel(
      writer.add_schema("uavmot::msg::MotionEstimate", "omgidl", "struct MotionEstimate {};"), "uavmot/motion", "cdr", {});
  uavmot::msg::TrackListPubSubType tracks_type;
  uavmot::msg::MotionEstimatePubSubType motion_type;
  uint32_t sequence = 0;
  for (const auto& stream : streams) {
    for (auto [frame, list] : lists) {
      uavmot::MotionEstimate motion;
      motion.stream_id = stream;
      motion.frame_index = frame;
      motion.image_width = 320;
      motion.image_height = 240;
      motion.quality.valid = frame > 1;
      if (frame > 1) motion.homography = homographies.at(frame);
      auto motion_msg = uavmot::dds::to_msg(motion);
      const auto motion_bytes = uavmot::dds::to_cdr(motion_type, motion_msg);
      writer.write(motion_channel, ++sequence, static_cast<uint64_t>(frame) * 1000, 0, motion_bytes.data(), motion_bytes.size());
      if (!with_tracks) continue;
      list.stream_id = stream;
      list.frame_index = frame;
      auto tracks_msg = uavmot::dds::to_msg(list);
      const auto tracks_bytes = uavmot::dds::to_cdr(tracks_type, tracks_msg);
      writer.write(tracks_channel, ++sequence, static_cast<uint64_t>(frame) * 1000 + 1, 0, tracks_bytes.data(), tracks_bytes.size());
    }
  }
  writer.close();
}

TEST_F(EvalCli, ScoresARecordingWithoutResultFiles) {
  const std::string recording = (dir_ / "truth.mcap").string();
  write_truth_recording(seq(), recording, {"uav1"});
  const std::string json = (dir_ / "recording.json").string();
  const ProcessResult r = run_eval("--seq " + seq() + " --recording " + recording + " --json " + json);
  ASSERT_EQ(r.code, 0) << r.output;
  std::ifstream in(json);
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_DOUBLE_EQ(j["tracking"][0]["MOTA"].get<double>(), 1.0);
  EXPECT_DOUBLE_EQ(j["tracking"][0]["IDF1"].get<double>(), 1.0);
  EXPECT_NEAR(j["homography"]["max_px"].get<double>(), 0.0, 1e-9);
  EXPECT_EQ(j["false_alarms"]["false_alarms"].get<int>(), 0);

  // Several streams: one is chosen, or the error names them.
  const std::string two = (dir_ / "two.mcap").string();
  write_truth_recording(seq(), two, {"uav1", "uav2"});
  ProcessResult several = run_eval("--seq " + seq() + " --recording " + two);
  EXPECT_NE(several.code, 0);
  EXPECT_NE(several.output.find("several streams (uav1, uav2): choose one with --stream-id"), std::string::npos) << several.output;
  EXPECT_EQ(run_eval("--seq " + seq() + " --recording " + two + " --stream-id uav2").code, 0);
  several = run_eval("--seq " + seq() + " --recording " + two + " --stream-id uav3");
  EXPECT_NE(several.output.find("no stream 'uav3'"), std::string::npos) << several.output;

  // A recording without tracks, a file that is not MCAP, and files given beside a recording.
  const std::string no_tracks = (dir_ / "motion_only.mcap").string();
  write_truth_recording(seq(), no_tracks, {"uav1"}, false);
  ProcessResult bad = run_eval("--seq " + seq() + " --recording " + no_tracks);
  EXPECT_NE(bad.code, 0);
  EXPECT_NE(bad.output.find("has no uavmot/tracks topic"), std::string::npos) << bad.output;
  bad = run_eval("--seq " + seq() + " --recording " + seq() + "/gt/gt.txt");
  EXPECT_NE(bad.code, 0);
  EXPECT_NE(bad.output.find("gt.txt"), std::string::npos) << bad.output;
  bad = run_eval("--seq " + seq() + " --recording " + recording + " --pred " + seq() + "/gt/gt.txt");
  EXPECT_NE(bad.code, 0);
  EXPECT_NE(bad.output.find("excludes"), std::string::npos) << bad.output;
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
