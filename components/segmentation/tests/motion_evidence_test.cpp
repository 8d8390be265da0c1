// Motion evidence: where around a region the pixels move with its cluster.

#include "../src/motion_evidence.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "synthetic.hpp"

namespace uavmot::segmentation {
namespace {

using testing::translation;
using testing::two_frames;
using testing::TwoFrames;

// The current frame's window around the car, and the previous frame's, as the segmenter keeps them.
struct Windows {
  ImageCrop current;
  std::vector<ImageCrop> previous;
};

Windows windows_of(const TwoFrames& f) {
  return {{cv::Rect(60, 50, 80, 60), f.current(cv::Rect(60, 50, 80, 60))},
          {{cv::Rect(50, 40, 90, 70), f.previous(cv::Rect(50, 40, 90, 70))}}};
}

const Homography kPreviousFromCurrent = translation(-3.0, -3.0);  // the camera moved by (3, 3) px

// A car painted like the road (mean grey 100) beside static ground texture: the region found sits
// half on the car and half beside it, as a road-grey car's blob that took in the marking does.
TEST(MotionEvidence, ARegionBesideItsCarIsPulledOntoTheCar) {
  for (const cv::Vec2d& velocity : {cv::Vec2d(1.0, 0.0), cv::Vec2d(0.5, 0.0), cv::Vec2d(-0.8, 0.1)}) {
    SCOPED_TRACE(velocity);
    const TwoFrames f = two_frames(velocity, 100.0);
    const Windows w = windows_of(f);
    for (const double across : {-4.0, 4.0}) {
      SCOPED_TRACE(across);
      OrientedBox beside = f.body;
      beside.cy += across;
      const auto e = motion_evidence(w.current, beside, 6.0, {velocity, 0.5, 0.3}, kPreviousFromCurrent, w.previous);
      ASSERT_TRUE(e.has_value());
      EXPECT_LT(e->inside_fraction, 0.6);
      EXPECT_NEAR(e->across_px, -across, 1.0) << "onto the car";
    }
  }
}

// Across a turned box too: the car's box turned by 180 degrees has its across axis the other way.
TEST(MotionEvidence, ARegionOnItsCarStaysThere) {
  const cv::Vec2d velocity(1.0, 0.0);
  const TwoFrames f = two_frames(velocity);
  const Windows w = windows_of(f);
  OrientedBox turned = f.body;
  turned.cy += 3.0;
  turned.angle_deg = 180.0;
  const auto t = motion_evidence(w.current, turned, 6.0, {velocity, 0.5, 0.3}, kPreviousFromCurrent, w.previous);
  ASSERT_TRUE(t.has_value());
  EXPECT_NEAR(t->across_px, 3.0, 1.0) << "its +y side is the image's -y";
  const auto e = motion_evidence(w.current, f.body, 6.0, {velocity, 0.5, 0.3}, kPreviousFromCurrent, w.previous);
  ASSERT_TRUE(e.has_value());
  EXPECT_GT(e->inside_fraction, 0.6);
  EXPECT_NEAR(e->across_px, 0.0, 0.5);
}

// A box around a car's one feature, at the car's end, lengthened past both its ends: the evidence
// lies along the box toward the car, and a few steps onto it end on the car (the segmenter's
// fallback for a cluster whose window gives no blob). Not lengthened, the box sees only its own part.
TEST(MotionEvidence, ABoxAtOneEndOfItsCarFindsTheCarAlongItsTravel) {
  for (const cv::Vec2d& velocity : {cv::Vec2d(1.0, 0.0), cv::Vec2d(0.6, 0.0)}) {
    SCOPED_TRACE(velocity);
    const TwoFrames f = two_frames(velocity, 100.0);
    const Windows w = windows_of(f);
    for (const double along : {-7.0, 7.0}) {
      SCOPED_TRACE(along);
      OrientedBox box = f.body;
      box.cx += along;
      const auto first = motion_evidence(w.current, box, 3.0, {velocity, 0.5, 0.3}, kPreviousFromCurrent, w.previous, 7.5);
      ASSERT_TRUE(first.has_value());
      EXPECT_LT(first->along_px * along, 0.0) << "toward the car";
      EXPECT_GT(std::abs(first->along_px), 2.0);
      for (int step = 0; step < 3; ++step) {
        const auto e = motion_evidence(w.current, box, 3.0, {velocity, 0.5, 0.3}, kPreviousFromCurrent, w.previous, 7.5);
        ASSERT_TRUE(e.has_value());
        box.cx += e->along_px;
        box.cy += e->across_px;
      }
      EXPECT_NEAR(box.cx, f.body.cx, 1.5);
      EXPECT_NEAR(box.cy, f.body.cy, 1.0);
      const auto own = motion_evidence(w.current, f.body, 3.0, {velocity, 0.5, 0.3}, kPreviousFromCurrent, w.previous);
      ASSERT_TRUE(own.has_value());
      OrientedBox unlengthened = f.body;
      unlengthened.cx += along;
      const auto short_box = motion_evidence(w.current, unlengthened, 3.0, {velocity, 0.5, 0.3}, kPreviousFromCurrent, w.previous);
      ASSERT_TRUE(short_box.has_value());
      EXPECT_LT(std::abs(short_box->along_px), std::abs(first->along_px));
    }
  }
}

// Static texture is explained by the previous frame at rest: it gives no evidence at all, so a
// region on the ground away from any car is not moved anywhere.
TEST(MotionEvidence, StaticGroundGivesNone) {
  const cv::Vec2d velocity(1.0, 0.0);
  const TwoFrames f = two_frames(velocity);
  const Windows w = windows_of(f);
  OrientedBox ground = f.body;
  ground.cy += 20.0;
  EXPECT_FALSE(motion_evidence(w.current, ground, 6.0, {velocity, 0.5, 0.3}, kPreviousFromCurrent, w.previous));
}

TEST(MotionEvidence, NothingWithoutAFastEnoughShiftOrThePreviousPixels) {
  const cv::Vec2d velocity(1.0, 0.0);
  const TwoFrames f = two_frames(velocity);
  const Windows w = windows_of(f);
  EXPECT_FALSE(motion_evidence(w.current, f.body, 6.0, {{0.1, 0.0}, 0.0, 0.3}, kPreviousFromCurrent, w.previous));
  EXPECT_FALSE(motion_evidence(w.current, f.body, 6.0, {velocity, 0.5, 0.3}, kPreviousFromCurrent, {}));
  // The previous frame's window ends left of where the car was.
  EXPECT_FALSE(motion_evidence(w.current, f.body, 6.0, {velocity, 0.5, 0.3}, kPreviousFromCurrent,
                               {{cv::Rect(0, 0, 80, 160), f.previous(cv::Rect(0, 0, 80, 160))}}));
  OrientedBox outside = f.body;  // outside the current window
  outside.cx = 10.0;
  EXPECT_FALSE(motion_evidence(w.current, outside, 6.0, {velocity, 0.5, 0.3}, kPreviousFromCurrent, w.previous));
  OrientedBox broken = f.body;
  broken.cy = std::nan("");
  EXPECT_FALSE(motion_evidence(w.current, broken, 6.0, {velocity, 0.5, 0.3}, kPreviousFromCurrent, w.previous));
}

}  // namespace
}  // namespace uavmot::segmentation
