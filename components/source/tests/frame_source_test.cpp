#include "uavmot/source/frame_source.hpp"

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "uavmot/build_paths/build_paths.hpp"
#include "uavmot/core/error.hpp"
#include "uavmot/source/frame_prefetcher.hpp"
#include "uavmot/source/sequence_info.hpp"
#include "scratch_dir.hpp"

namespace uavmot::source {
namespace {
namespace fs = std::filesystem;

const fs::path kClif = fs::path(build_paths::data_dir()) / "clif2007" / "jpg";
const fs::path kAphillMp4 = fs::path(build_paths::data_dir()) / "aphill" / "aphill_240_1fps_crf32.mp4";

fs::path fresh_dir(const std::string& name) {
  return test_support::fresh_scratch_dir("source_" + name);
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

int64_t drain(FrameSource& source) {
  Frame frame;
  int64_t n = 0;
  while (source.next(frame)) ++n;
  return n;
}

TEST(FrameSource, ReadsImageFolderInOrderWithOneBasedIndices) {
  auto source = open_frame_source({.path = kClif.string(), .max_frames = 5});
  EXPECT_EQ(source->info().kind, "images");
  EXPECT_EQ(source->info().frame_count, 5);
  EXPECT_EQ(source->info().size, cv::Size(668, 1004));
  Frame frame;
  for (int i = 1; i <= 5; ++i) {
    ASSERT_TRUE(source->next(frame));
    EXPECT_EQ(frame.index, i);
    EXPECT_EQ(frame.image.type(), CV_8UC1);
    EXPECT_EQ(frame.capture_time_ns, static_cast<int64_t>((i - 1) * 1e9 / 25.0 + 0.5));
  }
  EXPECT_FALSE(source->next(frame));
  // The first frame is the first file in sorted order.
  const cv::Mat expected = cv::imread((kClif / "000000-100006.jpg").string(), cv::IMREAD_GRAYSCALE);
  auto again = open_frame_source({.path = kClif.string(), .max_frames = 1});
  ASSERT_TRUE(again->next(frame));
  EXPECT_EQ(cv::norm(frame.image, expected, cv::NORM_INF), 0.0);
}

TEST(FrameSource, StartFrameLoopAndColor) {
  auto source = open_frame_source({.path = kClif.string(), .start_frame = 249, .max_frames = 5, .loop = true,
                                   .color = ColorMode::Color});
  Frame frame;
  ASSERT_TRUE(source->next(frame));
  EXPECT_EQ(frame.image.type(), CV_8UC3);
  const cv::Mat f249 = frame.image.clone();
  EXPECT_TRUE(source->next(frame));  // 250
  EXPECT_TRUE(source->next(frame));  // loops back to 249
  EXPECT_EQ(frame.index, 3);
  EXPECT_EQ(cv::norm(frame.image, f249, cv::NORM_INF), 0.0);
  EXPECT_EQ(drain(*source), 2);
}

TEST(FrameSource, ReadsVideoWithItsFrameRate) {
  auto source = open_frame_source({.path = kAphillMp4.string()});
  EXPECT_EQ(source->info().kind, "video");
  EXPECT_DOUBLE_EQ(source->info().fps, 1.0);
  EXPECT_EQ(source->info().size, cv::Size(360, 240));
  EXPECT_EQ(drain(*source), 310);
}

TEST(FrameSource, ReadsMotChallengeSequenceAndItsGsd) {
  const fs::path seq = fresh_dir("mot");
  fs::create_directories(seq / "img1");
  for (int i = 1; i <= 3; ++i) {
    cv::Mat img(48, 64, CV_8UC3, cv::Scalar(i * 10, 0, 0));
    char name[32];
    std::snprintf(name, sizeof(name), "%06d.png", i);
    cv::imwrite((seq / "img1" / name).string(), img);
  }
  std::ofstream(seq / "seqinfo.ini") << "[Sequence]\nname=t\nimDir=img1\nframeRate=30\nseqLength=3\nimWidth=64\n"
                                        "imHeight=48\nimExt=.png\ngsd=0.35\n";
  auto source = open_frame_source({.path = seq.string()});
  EXPECT_EQ(source->info().kind, "mot");
  EXPECT_DOUBLE_EQ(source->info().fps, 30.0);
  EXPECT_DOUBLE_EQ(source->info().gsd_m, 0.35);
  EXPECT_EQ(drain(*source), 3);
}


// Live mode passes over frames it is late for: their indices are used up, the frames after them
// are the same images with the same indices and capture times as without skipping.
TEST(FrameSource, SkipKeepsInputNumberingForImagesAndVideo) {
  for (const fs::path& input : {kClif, kAphillMp4}) {
    SCOPED_TRACE(input.string());
    auto plain = open_frame_source({.path = input.string(), .max_frames = 8});
    std::vector<Frame> all;
    for (Frame f; plain->next(f);) all.push_back({f.stream_id, f.index, f.capture_time_ns, f.image.clone()});
    ASSERT_EQ(all.size(), 8u);

    auto skipping = open_frame_source({.path = input.string(), .max_frames = 8});
    Frame frame;
    ASSERT_TRUE(skipping->next(frame));  // 1
    ASSERT_TRUE(skipping->skip());       // 2
    ASSERT_TRUE(skipping->skip());       // 3
    ASSERT_TRUE(skipping->next(frame));  // 4
    EXPECT_EQ(frame.index, 4);
    EXPECT_EQ(frame.capture_time_ns, all[3].capture_time_ns);
    EXPECT_EQ(cv::norm(frame.image, all[3].image, cv::NORM_INF), 0.0);
    for (int i = 5; i <= 7; ++i) ASSERT_TRUE(skipping->skip());
    ASSERT_TRUE(skipping->next(frame));  // 8, the last one of max_frames
    EXPECT_EQ(frame.index, 8);
    EXPECT_EQ(cv::norm(frame.image, all[7].image, cv::NORM_INF), 0.0);
    EXPECT_FALSE(skipping->skip()) << "skip stops at the frame limit like next()";
    EXPECT_FALSE(skipping->next(frame));
  }
  // At the end of a looping input, skip starts again from the first frame like next().
  auto looping = open_frame_source({.path = kClif.string(), .start_frame = 249, .max_frames = 4, .loop = true});
  Frame frame;
  ASSERT_TRUE(looping->skip());  // 249
  ASSERT_TRUE(looping->skip());  // 250
  ASSERT_TRUE(looping->skip());  // 249 again
  ASSERT_TRUE(looping->next(frame));
  EXPECT_EQ(frame.index, 4);
  const cv::Mat f250 = cv::imread((kClif / "000000-100255.jpg").string(), cv::IMREAD_GRAYSCALE);  // the 250th file
  ASSERT_FALSE(f250.empty());
  EXPECT_EQ(cv::norm(frame.image, f250, cv::NORM_INF), 0.0);
}
TEST(FrameSourceBadInput, MissingPath) {
  EXPECT_NE(error_of([] { open_frame_source({.path = "/nonexistent/video.mp4"}); }).find("does not exist"),
            std::string::npos);
}

TEST(FrameSourceBadInput, EmptyDirectory) {
  const fs::path dir = fresh_dir("empty");
  EXPECT_NE(error_of([&] { open_frame_source({.path = dir.string()}); }).find("no images"), std::string::npos);
}

TEST(FrameSourceBadInput, NotAVideo) {
  const fs::path dir = fresh_dir("notvideo");
  std::ofstream(dir / "clip.mp4") << "this is not a video";
  EXPECT_NE(error_of([&] { open_frame_source({.path = (dir / "clip.mp4").string()}); }).find("cannot open video"),
            std::string::npos);
}

TEST(FrameSourceBadInput, TruncatedVideoDeliversWhatItCanThenFails) {
  // A streamable mp4 (index first) cut in half: the first frames decode, then a clear error.
  const fs::path dir = fresh_dir("truncated");
  const fs::path whole = dir / "whole.mp4";
  const std::string cmd = "ffmpeg -loglevel error -y -i '" + kAphillMp4.string() +
                          "' -c copy -movflags +faststart '" + whole.string() + "'";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  const auto size = fs::file_size(whole);
  fs::copy_file(whole, dir / "cut.mp4");
  fs::resize_file(dir / "cut.mp4", size / 2);
  auto source = open_frame_source({.path = (dir / "cut.mp4").string()});
  Frame frame;
  int64_t delivered = 0;
  const std::string error = error_of([&] {
    while (source->next(frame)) ++delivered;
  });
  EXPECT_NE(error.find("truncated or corrupt"), std::string::npos) << error;
  EXPECT_GT(delivered, 50);
  EXPECT_LT(delivered, 310);
}

TEST(FrameSourceBadInput, CorruptImageIsNamedOrSkipped) {
  const fs::path dir = fresh_dir("corrupt");
  for (int i = 1; i <= 4; ++i) {
    fs::copy_file(kClif / ("000000-10000" + std::to_string(5 + i) + ".jpg"), dir / ("f" + std::to_string(i) + ".jpg"));
  }
  std::ofstream(dir / "f3.jpg", std::ios::trunc) << "garbage, not a jpeg";
  auto strict = open_frame_source({.path = dir.string()});
  Frame frame;
  const std::string error = error_of([&] { drain(*strict); });
  EXPECT_NE(error.find("f3.jpg"), std::string::npos) << error;

  auto lenient = open_frame_source({.path = dir.string(), .skip_corrupt = true});
  EXPECT_EQ(drain(*lenient), 3);
  EXPECT_EQ(lenient->skipped(), 1);
}

// Reading ahead changes nothing about the frames: same images, indices and capture times, in order.
TEST(FramePrefetcher, DeliversTheSourcesFramesInOrderAndSkipsWhatItIsTold) {
  auto plain = open_frame_source({.path = kClif.string(), .max_frames = 20});
  FramePrefetcher ahead(open_frame_source({.path = kClif.string(), .max_frames = 20}), 3);
  Frame a, b;
  int64_t n = 0;
  while (plain->next(a)) {
    ASSERT_TRUE(ahead.next(b));
    EXPECT_EQ(b.index, a.index);
    EXPECT_EQ(b.capture_time_ns, a.capture_time_ns);
    EXPECT_EQ(cv::norm(a.image, b.image, cv::NORM_INF), 0.0);
    ++n;
  }
  EXPECT_FALSE(ahead.next(b));
  EXPECT_EQ(n, 20);

  // Asked before each read: odd frames are passed over undecoded and counted.
  FramePrefetcher skipping(open_frame_source({.path = kClif.string(), .max_frames = 10}), 2,
                           [](int64_t index) { return index % 2 == 1; });
  std::vector<int64_t> indices;
  while (skipping.next(b)) indices.push_back(b.index);
  EXPECT_EQ(indices, (std::vector<int64_t>{2, 4, 6, 8, 10}));
  EXPECT_EQ(skipping.skipped_undecoded(), 5);
  EXPECT_EQ(skipping.last_index(), 10);
}

TEST(FramePrefetcher, ReportsABrokenInputAfterTheFramesBeforeIt) {
  const fs::path dir = fresh_dir("prefetch_corrupt");
  for (int i = 1; i <= 4; ++i) {
    fs::copy_file(kClif / ("000000-10000" + std::to_string(5 + i) + ".jpg"), dir / ("f" + std::to_string(i) + ".jpg"));
  }
  std::ofstream(dir / "f3.jpg", std::ios::trunc) << "garbage, not a jpeg";
  FramePrefetcher ahead(open_frame_source({.path = dir.string()}), 3);
  Frame frame;
  int64_t delivered = 0;
  const std::string error = error_of([&] {
    while (ahead.next(frame)) ++delivered;
  });
  EXPECT_EQ(delivered, 2);
  EXPECT_NE(error.find("f3.jpg"), std::string::npos) << error;
  // Stopping early (the destructor) must not hang on a reader that waits for room.
  FramePrefetcher abandoned(open_frame_source({.path = kClif.string()}), 2);
  ASSERT_TRUE(abandoned.next(frame));
}

TEST(FrameSourceBadInput, MalformedSeqinfo) {
  const fs::path seq = fresh_dir("badseq");
  fs::create_directories(seq / "img1");
  std::ofstream(seq / "seqinfo.ini") << "[Sequence]\nframeRate=fast\n";
  EXPECT_NE(error_of([&] { read_sequence_info(seq.string()); }).find("seqinfo.ini:2"), std::string::npos);
}

TEST(FrameSourceBadInput, StartBeyondEnd) {
  EXPECT_NE(error_of([] { open_frame_source({.path = kClif.string(), .start_frame = 1000}); }).find("beyond"),
            std::string::npos);
}

}  // namespace
}  // namespace uavmot::source
