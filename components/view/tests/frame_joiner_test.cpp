// FrameJoiner pairs frames with their results in order, waits for tracks a bounded time, and
// never holds more than a bounded number of frames.

#include <gtest/gtest.h>

#include "uavmot/view/frame_joiner.hpp"

namespace uavmot::view {
namespace {

Frame frame(int64_t i) {
  Frame f;
  f.index = i;
  f.image = cv::Mat(4, 4, CV_8UC1, cv::Scalar(static_cast<double>(i)));
  return f;
}
TrackList tracks(int64_t i) {
  TrackList t;
  t.frame_index = i;
  return t;
}
MotionEstimate motion(int64_t i) {
  MotionEstimate m;
  m.frame_index = i;
  return m;
}
std::vector<int64_t> indices(const std::vector<JoinedFrame>& frames) {
  std::vector<int64_t> out;
  for (const auto& f : frames) out.push_back(f.frame.index);
  return out;
}

TEST(FrameJoiner, ReleasesAFrameWhenItsTracksArrive) {
  FrameJoiner joiner(5);
  joiner.add_frame(frame(1));
  joiner.add_frame(frame(2));
  joiner.add_motion(motion(1));
  EXPECT_TRUE(joiner.pop_ready().empty());
  joiner.add_tracks(tracks(2));  // 2 is complete but 1 is not: order is kept
  EXPECT_TRUE(joiner.pop_ready().empty());
  joiner.add_tracks(tracks(1));
  const auto ready = joiner.pop_ready();
  ASSERT_EQ(indices(ready), (std::vector<int64_t>{1, 2}));
  EXPECT_TRUE(ready[0].motion.has_value());
  EXPECT_FALSE(ready[1].motion.has_value());
  EXPECT_EQ(ready[0].frame.image.at<uint8_t>(0, 0), 1);
  EXPECT_EQ(joiner.pending(), 0u);
  EXPECT_EQ(joiner.released_incomplete(), 0u);
}

TEST(FrameJoiner, FramesOlderThanTheLagAreDrawnWithWhatArrived) {
  FrameJoiner joiner(3);
  joiner.add_frame(frame(1));
  joiner.add_motion(motion(1));
  joiner.add_frame(frame(2));
  joiner.add_frame(frame(3));
  EXPECT_TRUE(joiner.pop_ready().empty());
  joiner.add_frame(frame(4));  // 1 is now 3 frames old
  const auto ready = joiner.pop_ready();
  ASSERT_EQ(indices(ready), (std::vector<int64_t>{1}));
  EXPECT_TRUE(ready[0].motion.has_value());
  EXPECT_FALSE(ready[0].tracks.has_value());
  EXPECT_EQ(joiner.released_incomplete(), 1u);
  // Its tracks arriving late are discarded, not drawn on a later frame.
  joiner.add_tracks(tracks(1));
  EXPECT_EQ(joiner.discarded(), 1u);
  EXPECT_EQ(joiner.pending(), 3u);
}

TEST(FrameJoiner, ResultsWithoutAFrameDoNotBlockOrGrowForever) {
  FrameJoiner joiner(2);
  joiner.add_tracks(tracks(1));  // frame 1 was dropped upstream
  joiner.add_frame(frame(2));
  joiner.add_tracks(tracks(2));
  EXPECT_TRUE(joiner.pop_ready().empty());  // frame 1 might still come
  joiner.add_frame(frame(3));
  EXPECT_EQ(indices(joiner.pop_ready()), (std::vector<int64_t>{2}));
  EXPECT_EQ(joiner.discarded(), 1u);
  // No frames at all: the buffer stays bounded.
  for (int64_t i = 10; i < 100; ++i) {
    joiner.add_tracks(tracks(i));
    joiner.pop_ready();
  }
  EXPECT_LE(joiner.pending(), 2u * 2 + 9);
}

TEST(FrameJoiner, FlushReleasesEveryFrameInOrder) {
  FrameJoiner joiner(10);
  joiner.add_frame(frame(3));
  joiner.add_frame(frame(1));
  joiner.add_motion(motion(2));
  joiner.add_frame(frame(2));
  EXPECT_EQ(indices(joiner.flush()), (std::vector<int64_t>{1, 2, 3}));
  EXPECT_EQ(joiner.pending(), 0u);
  joiner.add_frame(frame(2));  // after a flush, old indices are late
  EXPECT_EQ(joiner.discarded(), 1u);
}

}  // namespace
}  // namespace uavmot::view
