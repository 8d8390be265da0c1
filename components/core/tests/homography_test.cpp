#include "uavmot/core/homography.hpp"

#include <cmath>

#include <gtest/gtest.h>

namespace uavmot {
namespace {

TEST(Homography, NormalizeDividesByH33AndRejectsDegenerate) {
  Homography h(2, 0, 4, 0, 2, 6, 0, 0, 2);
  ASSERT_TRUE(normalize_homography(h));
  EXPECT_DOUBLE_EQ(h(0, 2), 2.0);
  EXPECT_DOUBLE_EQ(h(2, 2), 1.0);
  Homography zero(1, 0, 0, 0, 1, 0, 0, 0, 0);
  EXPECT_FALSE(normalize_homography(zero));
  Homography nan(1, 0, NAN, 0, 1, 0, 0, 0, 1);
  EXPECT_FALSE(normalize_homography(nan));
}

TEST(Homography, TransformBoxUnderRotationAndScale) {
  const double a = 30.0 * M_PI / 180.0;
  const double s = 2.0;
  const Homography h(s * std::cos(a), -s * std::sin(a), 5, s * std::sin(a), s * std::cos(a), 7, 0, 0, 1);
  const OrientedBox box{10, 0, 2, 6, 0};
  const auto out = transform_box(h, box);
  const auto c = apply_homography(h, {10, 0});
  EXPECT_NEAR(out.cx, c.x, 1e-9);
  EXPECT_NEAR(out.cy, c.y, 1e-9);
  EXPECT_NEAR(out.length, 12, 1e-9);
  EXPECT_NEAR(out.width, 4, 1e-9);
  EXPECT_NEAR(out.angle_deg, 30, 1e-9);
}

TEST(Homography, JacobianMatchesFiniteDifferences) {
  const Homography h(1.01, 0.02, 3, -0.01, 0.99, -2, 1e-5, -2e-5, 1);
  const cv::Point2d p(300, 200);
  const auto jac = homography_jacobian(h, p);
  const double eps = 1e-4;
  const auto dx = (apply_homography(h, p + cv::Point2d(eps, 0)) - apply_homography(h, p - cv::Point2d(eps, 0))) / (2 * eps);
  const auto dy = (apply_homography(h, p + cv::Point2d(0, eps)) - apply_homography(h, p - cv::Point2d(0, eps))) / (2 * eps);
  EXPECT_NEAR(jac(0, 0), dx.x, 1e-6);
  EXPECT_NEAR(jac(1, 0), dx.y, 1e-6);
  EXPECT_NEAR(jac(0, 1), dy.x, 1e-6);
  EXPECT_NEAR(jac(1, 1), dy.y, 1e-6);
}

TEST(Homography, TransferErrorOfPureShiftIsTheShift) {
  const Homography shifted(1, 0, 0.25, 0, 1, 0, 0, 0, 1);
  EXPECT_NEAR(mean_transfer_error(identity_homography(), shifted, 640, 480), 0.25, 1e-12);
  EXPECT_EQ(transfer_errors(identity_homography(), shifted, 640, 480, 4).size(), 16u);
}

TEST(Homography, FramesToCrossViewIsTheSmallerSideOverTheCentresStep) {
  const Homography left_20px(1, 0, -20, 0, 1, 0, 0, 0, 1);
  EXPECT_NEAR(frames_to_cross_view(left_20px, {800, 600}), 30.0, 1e-9);  // 600 px / 20 px per frame
  EXPECT_TRUE(std::isinf(frames_to_cross_view(identity_homography(), {800, 600})));
  EXPECT_TRUE(std::isinf(frames_to_cross_view(left_20px, {0, 0})));
}

TEST(Homography, GroundInViewCountsTheFramesSinceTheCameraUncoveredIt) {
  // The image moves 20 px left per frame: new ground comes in at the right edge.
  const Homography left_20px(1, 0, -20, 0, 1, 0, 0, 0, 1);
  const cv::Size image(800, 600);
  EXPECT_EQ(frames_ground_in_view(left_20px, {790, 300}, image, 8), 0);  // came in this frame
  EXPECT_EQ(frames_ground_in_view(left_20px, {750, 300}, image, 8), 2);  // at 770 and 790 before
  EXPECT_EQ(frames_ground_in_view(left_20px, {100, 300}, image, 8), 9);  // in view for longer
  EXPECT_EQ(frames_ground_in_view(identity_homography(), {799, 300}, image, 8), 9);  // a still camera
}

}  // namespace
}  // namespace uavmot
