// Same input -> bit-identical output; bgr8 and mono8 give the same result.
#include <cstring>
#include <deque>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "test_support.hpp"

namespace uavmot::motion {
namespace {

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

void expect_identical(const MotionEstimate& a, const MotionEstimate& b, uint64_t id_offset = 0) {
  ASSERT_EQ(a.frame_index, b.frame_index);
  for (int i = 0; i < 9; ++i) EXPECT_TRUE(same_bits(a.homography.val[i], b.homography.val[i])) << a.frame_index;
  EXPECT_EQ(a.quality.valid, b.quality.valid);
  EXPECT_EQ(a.quality.inliers, b.quality.inliers);
  EXPECT_TRUE(same_bits(a.quality.residual_px, b.quality.residual_px));
  ASSERT_EQ(a.features.size(), b.features.size()) << a.frame_index;
  for (size_t i = 0; i < a.features.size(); ++i) {
    const auto& fa = a.features[i];
    const auto& fb = b.features[i];
    EXPECT_EQ(fa.id + id_offset, fb.id);
    EXPECT_TRUE(same_bits(fa.position.x, fb.position.x) && same_bits(fa.position.y, fb.position.y));
    EXPECT_TRUE(same_bits(fa.velocity[0], fb.velocity[0]) && same_bits(fa.velocity[1], fb.velocity[1]));
    EXPECT_TRUE(same_bits(fa.velocity_sigma, fb.velocity_sigma));
    EXPECT_EQ(fa.age, fb.age);
    EXPECT_EQ(fa.moving, fb.moving);
  }
}

testing::WarpedSequence moving_scene() {
  testing::WarpedSequence sequence(test::camera(4.0, 0.1, {640, 480}));
  sequence.set_patches(testing::scatter_patches(sequence, 10, 10, 5, 0.3, 1.5, 5));
  return sequence;
}

TEST(Determinism, TwoRunsAreBitIdentical) {
  const auto sequence = moving_scene();
  const auto first = test::run(sequence, 20);
  const auto second = test::run(sequence, 20);
  int moving = 0;
  for (size_t k = 0; k < first.size(); ++k) {
    expect_identical(first[k], second[k]);
    for (const auto& f : first[k].features) moving += f.moving;
  }
  EXPECT_GT(moving, 0) << "the comparison should cover moving features too";
}

TEST(Determinism, FeatureIdsStartAtOneAndIncrease) {
  const auto estimates = test::run(moving_scene(), 6);
  ASSERT_FALSE(estimates[0].features.empty());
  EXPECT_EQ(estimates[0].features.front().id, 1u);
  for (const auto& e : estimates) {
    for (size_t i = 1; i < e.features.size(); ++i) EXPECT_LT(e.features[i - 1].id, e.features[i].id);
  }
  // Ages grow by one per frame for a surviving feature.
  const auto& f1 = estimates[4].features.front();
  for (const auto& f : estimates[5].features) {
    if (f.id == f1.id) {
      EXPECT_EQ(f.age, f1.age + 1);
    }
  }
}

TEST(Determinism, ResetGivesTheSameResultsWithLaterIds) {
  const auto sequence = moving_scene();
  MotionEstimator estimator(MotionOptions{});
  std::vector<MotionEstimate> first, second;
  for (int k = 1; k <= 8; ++k) first.push_back(estimator.process(test::make_frame(sequence.frame(k), k)));
  uint64_t max_id = 0;
  for (const auto& e : first) {
    for (const auto& f : e.features) max_id = std::max(max_id, f.id);
  }
  estimator.reset();
  for (int k = 1; k <= 8; ++k) second.push_back(estimator.process(test::make_frame(sequence.frame(k), k)));
  for (size_t k = 0; k < first.size(); ++k) expect_identical(first[k], second[k], max_id);
}

TEST(Determinism, Bgr8AndMono8GiveTheSameResult) {
  const auto sequence = moving_scene();
  MotionEstimator mono(MotionOptions{}), bgr(MotionOptions{});
  for (int k = 1; k <= 12; ++k) {
    const cv::Mat gray = sequence.frame(k);
    cv::Mat colour;
    cv::cvtColor(gray, colour, cv::COLOR_GRAY2BGR);
    ASSERT_EQ(colour.type(), CV_8UC3);
    expect_identical(mono.process(test::make_frame(gray, k)), bgr.process(test::make_frame(colour, k)));
  }
}

TEST(Determinism, CallerMayReuseItsFrameBuffer) {
  // A video source often decodes into the same buffer: the estimator must not keep a reference.
  const auto sequence = moving_scene();
  MotionEstimator reused(MotionOptions{}), fresh(MotionOptions{});
  cv::Mat buffer(480, 640, CV_8UC1);
  for (int k = 1; k <= 6; ++k) {
    const cv::Mat image = sequence.frame(k);
    image.copyTo(buffer);
    const auto a = reused.process(test::make_frame(buffer, k));
    buffer.setTo(0);
    expect_identical(a, fresh.process(test::make_frame(image, k)));
  }
}

TEST(Determinism, PreparedFramesGiveTheSameResult) {
  // The pipelined chain builds each frame's pyramid ahead, on another thread (prepare), in mono8
  // and bgr8; a frame prepare() leaves unprepared is refused by process() as without it.
  const auto sequence = moving_scene();
  MotionEstimator plain(MotionOptions{}), prepared(MotionOptions{});
  for (int k = 1; k <= 12; ++k) {
    cv::Mat image = sequence.frame(k);
    if (k % 3 == 0) cv::cvtColor(image, image, cv::COLOR_GRAY2BGR);
    const Frame frame = test::make_frame(image, k);
    PreparedFrame ahead = prepared.prepare(frame);
    expect_identical(plain.process(frame), prepared.process(frame, std::move(ahead)));
  }
  const Frame empty = test::make_frame(cv::Mat(), 13);
  EXPECT_THROW(prepared.process(empty, prepared.prepare(empty)), InputError);
}

TEST(Determinism, FramesPreparedAheadInRecycledBuffersGiveTheSameResult) {
  // As the pipelined chain does: frames prepared two ahead of process(), into the buffers of frames
  // process() has finished with, also when the frame size changes (the recycled buffers are then
  // the wrong size and are replaced).
  const auto sequence = moving_scene();
  MotionEstimator plain(MotionOptions{}), prepared(MotionOptions{});
  std::vector<Frame> frames;
  for (int k = 1; k <= 14; ++k) {
    cv::Mat image = sequence.frame(k);
    if (k > 8) image = image(cv::Rect(10, 20, image.cols - 40, image.rows - 30)).clone();
    frames.push_back(test::make_frame(image, k));
  }
  std::deque<PreparedFrame> ahead;
  size_t next = 0;
  for (const Frame& frame : frames) {
    while (ahead.size() < 3 && next < frames.size()) ahead.push_back(prepared.prepare(frames[next++]));
    PreparedFrame mine = std::move(ahead.front());
    ahead.pop_front();
    expect_identical(plain.process(frame), prepared.process(frame, std::move(mine)));
  }
}

}  // namespace
}  // namespace uavmot::motion
