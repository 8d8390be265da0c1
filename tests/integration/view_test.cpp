// The annotated video: `uavmot-view` on the distributed chain (real processes over Fast DDS) and
// `uavmot process --video`, each giving an mp4 with one frame per input frame at the input's size.

#include <cstdio>
#include <filesystem>
#include <memory>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>

#include "child_process.hpp"
#include "uavmot/build_paths/build_paths.hpp"

namespace uavmot {
namespace {
using testing::binary;
using testing::ChildProcess;
namespace fs = std::filesystem;

constexpr int kFrames = 60;

struct VideoFacts {
  int frames = 0;
  cv::Size size;
  bool bright_green = false;  // some track was drawn
};

VideoFacts read_video(const std::string& path) {
  VideoFacts facts;
  cv::VideoCapture capture(path, cv::CAP_FFMPEG);
  if (!capture.isOpened()) return facts;
  cv::Mat frame;
  while (capture.read(frame)) {
    if (facts.frames++ == 0) facts.size = frame.size();
    if (facts.bright_green) continue;
    cv::Mat green;
    cv::inRange(frame, cv::Scalar(0, 200, 0), cv::Scalar(90, 255, 90), green);
    facts.bright_green = cv::countNonZero(green) > 20;
  }
  return facts;
}

// "frames,width,height" from ffprobe, or "" when ffprobe is not installed.
std::string ffprobe(const std::string& path) {
  if (std::system("command -v ffprobe >/dev/null 2>&1") != 0) return "";
  const std::string command = "ffprobe -v error -count_frames -select_streams v:0 -show_entries "
                              "stream=nb_read_frames,width,height -of csv=p=0 '" + path + "'";
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(command.c_str(), "r"), pclose);
  std::string out;
  char buffer[256];
  while (pipe && fgets(buffer, sizeof buffer, pipe.get())) out += buffer;
  while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
  return out;
}

class AnnotatedVideo : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    root_ = testing::fresh_dir("view");
    sequence_ = root_ + "/paper";
    ChildProcess sim({binary("uavmot-sim"), "--preset", "paper", "--seed", "3", "--frames", std::to_string(kFrames), "--out", sequence_},
                     root_ + "/sim.log");
    ASSERT_EQ(sim.wait(std::chrono::seconds(120)), 0) << sim.log();
    const cv::Mat first = cv::imread(sequence_ + "/img1/000001.jpg");
    ASSERT_FALSE(first.empty());
    size_ = first.size();
  }
  static std::string root_, sequence_;
  static cv::Size size_;
};
std::string AnnotatedVideo::root_, AnnotatedVideo::sequence_;
cv::Size AnnotatedVideo::size_;

TEST_F(AnnotatedVideo, ProcessWritesOneFramePerInputFrame) {
  const std::string video = root_ + "/process/annotated.mp4";
  ChildProcess process({binary("uavmot-process"), sequence_, "--out", root_ + "/process", "--video", video, "--quiet"},
                       root_ + "/process.log");
  ASSERT_EQ(process.wait(std::chrono::seconds(240)), 0) << process.log();
  const VideoFacts facts = read_video(video);
  EXPECT_EQ(facts.frames, kFrames);
  EXPECT_EQ(facts.size, size_);
  EXPECT_TRUE(facts.bright_green) << "no confirmed track drawn in " << video;
  const std::string probed = ffprobe(video);
  if (!probed.empty()) {
    EXPECT_EQ(probed, std::to_string(size_.width) + "," + std::to_string(size_.height) + "," + std::to_string(kFrames));
  }
}

TEST_F(AnnotatedVideo, ProcessRefusesAnUnwritableVideoPath) {
  ChildProcess process({binary("uavmot-process"), sequence_, "--out", root_ + "/process_bad", "--video",
                        "/proc/uavmot-cannot-write/a.mp4", "--quiet", "--count", "3"},
                       root_ + "/process_bad.log");
  const auto code = process.wait(std::chrono::seconds(60));
  ASSERT_TRUE(code.has_value());
  EXPECT_EQ(*code, 2) << process.log();
  EXPECT_NE(process.log().find("/proc/uavmot-cannot-write/a.mp4"), std::string::npos) << process.log();
}

TEST_F(AnnotatedVideo, ViewNodeDrawsTheDistributedChainIntoAnMp4) {
  const std::string video = root_ + "/view/annotated.mp4";
  const std::string config = build_paths::source_dir() + "/bringup/chain.yaml";
  const std::vector<std::string> dds = {"--domain", "41", "--transport", "local", "--mode", "lossless"};
  auto with = [&](std::vector<std::string> argv) {
    argv.insert(argv.end(), dds.begin(), dds.end());
    return argv;
  };
  // The viewer replaces the sink at the end of the chain; lossless, so every frame must come out.
  ChildProcess view(with({binary("uavmot-view"), "--out", video, "--gsd", "0.3", "--fps", "25"}), root_ + "/view.log");
  ChildProcess tracking(with({binary("uavmot-tracking"), "--config", config, "--wait-subscribers", "1"}), root_ + "/tracking.log");
  ChildProcess segmentation(with({binary("uavmot-segmentation"), "--config", config, "--wait-subscribers", "2"}),
                            root_ + "/segmentation.log");
  ChildProcess motion(with({binary("uavmot-motion"), "--config", config, "--wait-subscribers", "3"}), root_ + "/motion.log");
  ChildProcess source(with({binary("uavmot-source"), sequence_, "--stream-id", "uav1", "--wait-subscribers", "3"}),
                      root_ + "/source.log");
  ASSERT_EQ(view.wait(std::chrono::seconds(240)), 0) << view.log() << source.log() << motion.log();
  EXPECT_EQ(source.wait(std::chrono::seconds(20)), 0) << source.log();
  for (auto* p : {&motion, &segmentation, &tracking}) EXPECT_EQ(p->wait(std::chrono::seconds(20)), 0) << p->log();
  EXPECT_NE(view.log().find(std::to_string(kFrames) + " frames -> " + video), std::string::npos) << view.log();
  EXPECT_EQ(view.log().find("drawn before their tracks"), std::string::npos) << view.log();
  const VideoFacts facts = read_video(video);
  EXPECT_EQ(facts.frames, kFrames);
  EXPECT_EQ(facts.size, size_);
  EXPECT_TRUE(facts.bright_green) << "no confirmed track drawn in " << video;
  const std::string probed = ffprobe(video);
  if (!probed.empty()) {
    EXPECT_EQ(probed, std::to_string(size_.width) + "," + std::to_string(size_.height) + "," + std::to_string(kFrames));
  }
}

TEST_F(AnnotatedVideo, ViewWithoutDisplayOrOutputIsAClearError) {
  ChildProcess view({binary("uavmot-view"), "--window", "--domain", "42"}, root_ + "/view_no_display.log", {{"DISPLAY", ""}});
  EXPECT_EQ(view.wait(std::chrono::seconds(20)), 2);
  EXPECT_NE(view.log().find("pass --out FILE.mp4"), std::string::npos) << view.log();
}

}  // namespace
}  // namespace uavmot
