// VideoSink writes mp4 files that OpenCV reads back frame for frame, and refuses bad paths clearly.

#include <filesystem>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "uavmot/build_paths/build_paths.hpp"
#include "uavmot/core/error.hpp"
#include "uavmot/view/video_sink.hpp"

namespace uavmot::view {
namespace {
namespace fs = std::filesystem;

std::string temp_path(const std::string& name) {
  const fs::path dir = fs::path(build_paths::binary_dir()) / "test_output" / "view";
  fs::create_directories(dir);
  return (dir / name).string();
}

// A bright square that moves one frame after the other, so frames differ.
cv::Mat test_frame(int i, cv::Size size) {
  cv::Mat frame(size, CV_8UC3, cv::Scalar(40, 40, 40));
  cv::rectangle(frame, cv::Rect(4 + 5 * i, 20, 16, 16), cv::Scalar(0, 255, 0), cv::FILLED);
  return frame;
}

class VideoSinkCodec : public ::testing::TestWithParam<std::string> {};

TEST_P(VideoSinkCodec, RoundTripKeepsEveryFrameAndTheSize) {
  const std::string path = temp_path("roundtrip_" + GetParam() + ".mp4");
  fs::remove(path);
  const cv::Size size(160, 120);
  {
    VideoSink sink({path, 25.0, GetParam()});
    for (int i = 0; i < 20; ++i) sink.write(test_frame(i, size));
    EXPECT_EQ(sink.frames_written(), 20);
  }  // destructor closes
  cv::VideoCapture capture(path, cv::CAP_FFMPEG);
  ASSERT_TRUE(capture.isOpened()) << path;
  EXPECT_EQ(capture.get(cv::CAP_PROP_FRAME_WIDTH), 160);
  EXPECT_EQ(capture.get(cv::CAP_PROP_FRAME_HEIGHT), 120);
  EXPECT_NEAR(capture.get(cv::CAP_PROP_FPS), 25.0, 0.01);
  int frames = 0;
  cv::Mat frame;
  while (capture.read(frame)) {
    ASSERT_EQ(frame.size(), size);
    // The square is where it was drawn (lossy codec: compare roughly).
    const cv::Vec3b centre = frame.at<cv::Vec3b>(28, 12 + 5 * frames);
    EXPECT_GT(centre[1], 180) << "frame " << frames;
    EXPECT_LT(centre[2], 90) << "frame " << frames;
    ++frames;
  }
  EXPECT_EQ(frames, 20);
}

INSTANTIATE_TEST_SUITE_P(Mp4, VideoSinkCodec, ::testing::Values("mp4v", "avc1"));

TEST(VideoSink, MonoAndOtherSizedFramesAreConverted) {
  const std::string path = temp_path("mixed.mp4");
  {
    VideoSink sink({path, 10.0, "mp4v"});
    sink.write(cv::Mat(64, 80, CV_8UC1, cv::Scalar(128)));
    sink.write(cv::Mat(32, 40, CV_8UC3, cv::Scalar(0, 0, 200)));
    sink.close();
    sink.close();  // idempotent
    EXPECT_EQ(sink.frames_written(), 2);
  }
  cv::VideoCapture capture(path, cv::CAP_FFMPEG);
  ASSERT_TRUE(capture.isOpened());
  cv::Mat frame;
  int frames = 0;
  while (capture.read(frame)) {
    EXPECT_EQ(frame.size(), cv::Size(80, 64));
    ++frames;
  }
  EXPECT_EQ(frames, 2);
}

TEST(VideoSink, UnwritablePathsAreInputErrors) {
  try {
    VideoSink sink({"/proc/uavmot-cannot-write/out.mp4", 25.0, "mp4v"});
    FAIL() << "no error for an unwritable folder";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/proc/uavmot-cannot-write/out.mp4"), std::string::npos) << e.what();
  }
  EXPECT_THROW(VideoSink({fs::path(temp_path("x")).parent_path().string(), 25.0, "mp4v"}), InputError);  // a folder
  EXPECT_THROW(VideoSink({"", 25.0, "mp4v"}), InputError);
  EXPECT_THROW(VideoSink({temp_path("rate.mp4"), 0.0, "mp4v"}), InputError);
  EXPECT_THROW(VideoSink({temp_path("fourcc.mp4"), 25.0, "mp4"}), InputError);
}

TEST(VideoSink, NoFramesLeavesNoFile) {
  const std::string path = temp_path("empty.mp4");
  {
    VideoSink sink({path, 25.0, "mp4v"});
    EXPECT_TRUE(fs::exists(path));  // the path was checked by creating it
  }
  EXPECT_FALSE(fs::exists(path));
}

TEST(VideoSink, CreatesMissingFolders) {
  const fs::path dir = fs::path(temp_path("nested")) / "a" / "b";
  fs::remove_all(fs::path(temp_path("nested")));
  VideoSink sink({(dir / "v.mp4").string(), 25.0, "mp4v"});
  sink.write(test_frame(0, {64, 48}));
  sink.close();
  EXPECT_GT(fs::file_size(dir / "v.mp4"), 0u);
}

}  // namespace
}  // namespace uavmot::view
