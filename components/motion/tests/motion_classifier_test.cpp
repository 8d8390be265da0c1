// The moving/stationary decision: confirm_frames of evidence, or one frame of strong evidence.
#include <gtest/gtest.h>

#include "relative_velocity.hpp"
#include "uavmot/core/error.hpp"

namespace uavmot::motion {
namespace {

VelocityEstimate speed(double vx, double sigma = 0.05) {
  VelocityEstimate v;
  v.velocity = {vx, 0.0};
  v.sigma = sigma;
  v.available = true;
  return v;
}

MotionOptions options(double strong_motion_factor) {
  MotionOptions o;
  o.moving_sigma_factor = 4.0;  // threshold max(4 x 0.05, 0.15) = 0.2 px/frame
  o.min_moving_speed_px = 0.15;
  o.confirm_frames = 2;
  o.strong_motion_factor = strong_motion_factor;
  return o;
}

TEST(MotionClassifier, ASignificantSpeedNeedsConfirmFramesInARow) {
  MotionClassifier c;
  const MotionOptions o = options(0.0);
  EXPECT_FALSE(c.update(speed(1.0), 2, o));  // far above, but only one frame
  EXPECT_TRUE(c.update(speed(0.3), 3, o));
  MotionClassifier blip;
  EXPECT_FALSE(blip.update(speed(0.3), 2, o));
  EXPECT_FALSE(blip.update(speed(0.0), 3, o));  // the streak is broken
  EXPECT_FALSE(blip.update(speed(0.3), 4, o));
}

TEST(MotionClassifier, OneFrameAboveTheStrongFactorStartsMotionAtOnce) {
  const MotionOptions o = options(2.0);
  MotionClassifier car;
  EXPECT_TRUE(car.update(speed(0.45), 2, o));  // > 2 x 0.2
  MotionClassifier weak;
  EXPECT_FALSE(weak.update(speed(0.35), 2, o));  // significant, below 2 x the threshold: waits
  EXPECT_TRUE(weak.update(speed(0.35), 3, o));
  // The strong factor scales with the feature's own noise: the same speed with a noisy fit waits.
  MotionClassifier noisy;
  EXPECT_FALSE(noisy.update(speed(0.45, 0.1), 2, o));  // threshold 0.4, strong 0.8
}

TEST(MotionClassifier, OnlyANewFeatureStartsAtOnceAStillOneThatJumpsWaits) {
  const MotionOptions o = options(2.0);
  MotionClassifier still;  // sat still for a while, then one large step: a slip or a sliding silhouette
  EXPECT_FALSE(still.update(speed(0.0), 2, o));
  EXPECT_FALSE(still.update(speed(0.0), 3, o));
  EXPECT_FALSE(still.update(speed(1.0), 4, o));
  EXPECT_FALSE(still.update(speed(0.0), 5, o));
}

TEST(MotionClassifier, StoppingStillNeedsConfirmFramesAndYoungFeaturesNeverMove) {
  const MotionOptions o = options(2.0);
  MotionClassifier c;
  ASSERT_TRUE(c.update(speed(1.0), 2, o));
  EXPECT_TRUE(c.update(speed(0.0), 3, o));  // one slow frame does not stop it
  EXPECT_FALSE(c.update(speed(0.0), 4, o));
  MotionClassifier young;
  EXPECT_FALSE(young.update(speed(5.0), 1, o));  // seen in fewer than min_track_frames frames
}

TEST(MotionClassifier, TheStrongFactorIsOffOrAMultipleOfTheThreshold) {
  MotionOptions o;
  o.strong_motion_factor = 0.5;
  EXPECT_THROW(validate(o), InputError);
  o.strong_motion_factor = 1.0;
  EXPECT_NO_THROW(validate(o));
}

}  // namespace
}  // namespace uavmot::motion
