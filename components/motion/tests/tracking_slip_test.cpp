// A tracking slip (the LK window latching onto another corner) is told apart from motion.
#include <gtest/gtest.h>

#include "relative_velocity.hpp"

namespace uavmot::motion {
namespace {

VelocityEstimate known(double vx, double vy) {
  VelocityEstimate v;
  v.velocity = {vx, vy};
  v.available = true;
  return v;
}

TEST(TrackingSlip, AStepWhereCameraAndOwnMotionPutTheFeatureIsNoSlip) {
  const Homography pan(1, 0, -2.0, 0, 1, 0.5, 0, 0, 1);  // the camera moves: background shifts (-2, 0.5)
  // A car at 1.2 px/frame along x: it lands at (100 - 2 + 1.2, 50 + 0.5), give or take a pixel.
  EXPECT_FALSE(is_tracking_slip(pan, {100, 50}, {99.2f, 50.5f}, known(1.2, 0.0), 3.0));
  EXPECT_FALSE(is_tracking_slip(pan, {100, 50}, {100.5f, 51.5f}, known(1.2, 0.0), 3.0));
}

TEST(TrackingSlip, AJumpOfManyPixelsIsASlip) {
  // Seen on the reentry flight: a background feature 16 px from the border jumped 30 px in one frame.
  const Homography pan(1, 0, -1.4, 0, 1, 0.5, 0, 0, 1);
  EXPECT_TRUE(is_tracking_slip(pan, {782.2f, 752.1f}, {752.9f, 732.7f}, known(0.0, 0.0), 3.0));
}

TEST(TrackingSlip, UnknownVelocityOrADisabledCheckNeverCallsASlip) {
  const Homography still = identity_homography();
  EXPECT_FALSE(is_tracking_slip(still, {100, 50}, {130, 50}, VelocityEstimate{}, 3.0));  // first step of a new feature
  EXPECT_FALSE(is_tracking_slip(still, {100, 50}, {130, 50}, known(0.0, 0.0), 0.0));
}

}  // namespace
}  // namespace uavmot::motion
