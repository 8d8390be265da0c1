// The Kalman filter with the homography as control input: prediction, covariance, update, wrap-around.
#include <gtest/gtest.h>

#include <cmath>

#include "predictor.hpp"
#include "updater.hpp"

namespace uavmot::tracking {
namespace {

KalmanState car_state(double angle_deg = 30.0) {
  BoxMeasurementNoise noise;
  return initial_state(OrientedBox{100.0, 50.0, 5.0, 15.0, angle_deg}, cv::Vec2d(2.0, -1.0), 0.5, noise);
}

TEST(KalmanPredict, IdentityHomographyMovesByTheVelocity) {
  const KalmanState s = car_state();
  const KalmanState p = predict(s, identity_homography(), ProcessNoise{});
  EXPECT_NEAR(p.mean(kX), 102.0, 1e-9);
  EXPECT_NEAR(p.mean(kY), 49.0, 1e-9);
  EXPECT_NEAR(p.mean(kVx), 2.0, 1e-9);
  EXPECT_NEAR(p.mean(kVy), -1.0, 1e-9);
  EXPECT_NEAR(p.mean(kWidth), 5.0, 1e-9);
  EXPECT_NEAR(p.mean(kLength), 15.0, 1e-9);
  EXPECT_NEAR(p.mean(kAngle), 30.0, 1e-9);
}

TEST(KalmanPredict, TranslationHomographyShiftsPositionNotVelocity) {
  const Homography shift(1, 0, 7, 0, 1, -3, 0, 0, 1);
  const KalmanState p = predict(car_state(), shift, ProcessNoise{});
  EXPECT_NEAR(p.mean(kX), 109.0, 1e-9);  // 100 + 2 (object) + 7 (camera)
  EXPECT_NEAR(p.mean(kY), 46.0, 1e-9);   // 50 - 1 - 3
  EXPECT_NEAR(p.mean(kVx), 2.0, 1e-9);   // ground velocity is unchanged by a pure translation
  EXPECT_NEAR(p.mean(kVy), -1.0, 1e-9);
  EXPECT_NEAR(p.mean(kAngle), 30.0, 1e-9);
}

TEST(KalmanPredict, RotationAndZoomTurnVelocityAndBox) {
  // 90 deg rotation about the origin with zoom 2: (x, y) -> (-2y, 2x).
  const Homography rot_zoom(0, -2, 0, 2, 0, 0, 0, 0, 1);
  const KalmanState p = predict(car_state(30.0), rot_zoom, ProcessNoise{});
  EXPECT_NEAR(p.mean(kX), -2.0 * 49.0, 1e-6);
  EXPECT_NEAR(p.mean(kY), 2.0 * 102.0, 1e-6);
  EXPECT_NEAR(p.mean(kVx), 2.0, 1e-6);  // (2, -1) rotated by 90 deg and doubled = (2, 4)
  EXPECT_NEAR(p.mean(kVy), 4.0, 1e-6);
  EXPECT_NEAR(p.mean(kLength), 30.0, 1e-6);
  EXPECT_NEAR(p.mean(kWidth), 10.0, 1e-6);
  EXPECT_NEAR(axis_angle_difference_deg(p.mean(kAngle), 120.0), 0.0, 1e-6);
  // The position uncertainty scales with the zoom (variance x4) plus process noise.
  const KalmanState s = car_state(30.0);
  EXPECT_GT(p.covariance(kX, kX), 3.9 * s.covariance(kY, kY));
}

TEST(KalmanPredict, CovarianceGrowsWithoutMeasurements) {
  KalmanState s = car_state();
  double previous = s.covariance(kX, kX);
  for (int i = 0; i < 10; ++i) {
    s = predict(s, identity_homography(), ProcessNoise{});
    EXPECT_GT(s.covariance(kX, kX), previous);
    previous = s.covariance(kX, kX);
    EXPECT_TRUE(s.covariance.isApprox(s.covariance.transpose()));
  }
  // Velocity uncertainty feeds the position: after 10 frames it dominates the initial 1 px.
  EXPECT_GT(s.covariance(kX, kX), 10.0 * car_state().covariance(kX, kX));
}

TEST(KalmanPredict, JacobianMatchesConstantVelocityModelForIdentity) {
  const StateCovariance f = transition_jacobian(car_state().mean, identity_homography());
  StateCovariance expected = StateCovariance::Identity();
  expected(kX, kVx) = expected(kY, kVy) = 1.0;
  EXPECT_TRUE(f.isApprox(expected, 1e-6)) << f;
}

TEST(KalmanUpdate, BoxUpdateReducesCovarianceAndMovesTowardsMeasurement) {
  const KalmanState s = predict(car_state(), identity_homography(), ProcessNoise{});
  const OrientedBox measured{104.0, 49.5, 5.5, 16.0, 32.0};
  const KalmanState u = update_with_box(s, measured, BoxMeasurementNoise{}, 1.0);
  for (int i : {kX, kY, kWidth, kLength, kAngle}) EXPECT_LT(u.covariance(i, i), s.covariance(i, i)) << i;
  EXPECT_GT(u.mean(kX), s.mean(kX));
  EXPECT_LT(u.mean(kX), measured.cx);
  EXPECT_GT(u.mean(kAngle), 30.0);
  EXPECT_LT(u.mean(kAngle), 32.0);
}

TEST(KalmanUpdate, PositionUpdateReducesOnlyWhatItObserves) {
  const KalmanState s = predict(car_state(), identity_homography(), ProcessNoise{});
  const KalmanState u = update_with_position(s, {103.0, 49.0}, 1.0);
  EXPECT_LT(u.covariance(kX, kX), s.covariance(kX, kX));
  EXPECT_LT(u.covariance(kVx, kVx), s.covariance(kVx, kVx));  // correlated through the motion model
  EXPECT_DOUBLE_EQ(u.covariance(kWidth, kWidth), s.covariance(kWidth, kWidth));
  EXPECT_DOUBLE_EQ(u.mean(kLength), s.mean(kLength));
}

TEST(KalmanUpdate, AngleInnovationWrapsAroundNinetyDegrees) {
  // Track at 89 deg, region at -89 deg: the same axis 2 deg apart, not 178 deg.
  KalmanState s = car_state(89.0);
  const OrientedBox measured{100.0, 50.0, 5.0, 15.0, -89.0};
  const KalmanState u = update_with_box(s, measured, BoxMeasurementNoise{}, 1.0);
  EXPECT_LT(std::abs(axis_angle_difference_deg(u.mean(kAngle), 90.0)), 1.0);
  EXPECT_GT(u.mean(kAngle), -90.0);
  EXPECT_LE(u.mean(kAngle), 90.0);
}

TEST(KalmanUpdate, SwappedWidthAndLengthAreRelabelled) {
  // A region reported with the short side as "length" and the angle turned by 90 deg is the same box.
  const OrientedBox predicted{100.0, 50.0, 5.0, 15.0, 10.0};
  const OrientedBox swapped{100.0, 50.0, 15.0, 5.0, -80.0};
  const OrientedBox aligned = align_box_labelling(swapped, predicted);
  EXPECT_NEAR(aligned.length, 15.0, 1e-12);
  EXPECT_NEAR(aligned.width, 5.0, 1e-12);
  EXPECT_NEAR(axis_angle_difference_deg(aligned.angle_deg, 10.0), 0.0, 1e-12);
  const KalmanState s = car_state(10.0);
  const KalmanState u = update_with_box(s, swapped, BoxMeasurementNoise{}, 1.0);
  EXPECT_NEAR(u.mean(kLength), 15.0, 1e-6);
  EXPECT_NEAR(u.mean(kAngle), 10.0, 1e-6);
}

TEST(KalmanUpdate, NearSquareRegionBarelyMovesTheAngle) {
  const KalmanState s = car_state(0.0);
  const KalmanState elongated = update_with_box(s, OrientedBox{100, 50, 5, 15, 20}, BoxMeasurementNoise{}, 1.0);
  const KalmanState square = update_with_box(s, OrientedBox{100, 50, 9, 10, 20}, BoxMeasurementNoise{}, 1.0);
  EXPECT_GT(elongated.mean(kAngle), 5.0 * std::abs(square.mean(kAngle)));
}

TEST(KalmanUpdate, FeatureVelocityCorrectsAWrongVelocityAtOnce) {
  // The filter believes (2, -1) px/frame; the linked features say the car moves (0.5, 0.4).
  const KalmanState s = predict(car_state(), identity_homography(), ProcessNoise{});
  const KalmanState u = update_with_velocity(s, {0.5, 0.4}, 0.1);
  EXPECT_NEAR(u.mean(kVx), 0.5, 0.08);  // most of the 1.5 px/frame error gone in one update
  EXPECT_NEAR(u.mean(kVy), 0.4, 0.08);
  EXPECT_LT(u.covariance(kVx, kVx), 0.1 * 0.1);
  EXPECT_DOUBLE_EQ(u.mean(kLength), s.mean(kLength));  // velocity says nothing about size
}

TEST(KalmanUpdate, HeadingPullsTheAxisAcrossTheWrapAround) {
  // Axis at 85 deg, travel towards -88 deg (the same axis 7 deg on): the update turns through 90.
  const KalmanState s = car_state(85.0);
  const KalmanState u = update_with_heading(s, -88.0, 1.0);
  EXPECT_LT(std::abs(axis_angle_difference_deg(u.mean(kAngle), 92.0)), 1.0);
  EXPECT_LT(u.covariance(kAngle, kAngle), s.covariance(kAngle, kAngle));
}

TEST(KalmanUpdate, HeadingAcrossTheBoxRelabelsItInsteadOfTurningIt) {
  // A box 13.7 wide and 7.7 long at -41 deg is the same box as 7.7 x 13.7 at 49 deg; travelling along
  // 50 deg, the heading names its long side rather than dragging the axis through 90 deg.
  KalmanState s = initial_state(OrientedBox{100, 50, 13.7, 7.7, -41.0}, cv::Vec2d(0.65, 0.78), 0.1, BoxMeasurementNoise{});
  s.covariance(kWidth, kWidth) = 4.0;
  s.covariance(kLength, kLength) = 1.0;
  const KalmanState u = update_with_heading(s, 50.0, 10.0);
  EXPECT_NEAR(u.mean(kLength), 13.7, 1e-9);
  EXPECT_NEAR(u.mean(kWidth), 7.7, 1e-9);
  EXPECT_NEAR(u.covariance(kLength, kLength), 4.0, 1e-9);  // the variances travel with their sides
  EXPECT_NEAR(u.covariance(kWidth, kWidth), 1.0, 1e-9);
  EXPECT_GT(u.mean(kAngle), 49.0);
  EXPECT_LT(u.mean(kAngle), 50.0);
}

TEST(BoxAlongHeading, AnAlignedRegionIsUnchanged) {
  const OrientedBox region{100, 50, 5, 15, 30};
  const OrientedBox b = box_along_heading(region, 30.0 - 180.0);  // travelling the other way: same axis
  EXPECT_NEAR(b.width, 5.0, 1e-9);
  EXPECT_NEAR(b.length, 15.0, 1e-9);
  EXPECT_NEAR(axis_angle_difference_deg(b.angle_deg, 30.0), 0.0, 1e-9);
  EXPECT_DOUBLE_EQ(b.cx, 100.0);
  EXPECT_DOUBLE_EQ(b.cy, 50.0);
}

TEST(BoxAlongHeading, ABarAcrossTheCarBecomesItsWidth) {
  // A window bar 2 px long in the direction of travel and 5 px across it: width 5, length 2, angle = heading.
  const OrientedBox bar{100, 50, 2, 5, 90};
  const OrientedBox b = box_along_heading(bar, 0.0);
  EXPECT_NEAR(b.width, 5.0, 1e-9);
  EXPECT_NEAR(b.length, 2.0, 1e-9);
  EXPECT_NEAR(b.angle_deg, 0.0, 1e-9);
}

TEST(BoxAlongHeading, ATiltedRegionIsSpreadBetweenItsEllipseAndItsRectangle) {
  const OrientedBox region{0, 0, 5, 15, 30};
  const OrientedBox b = box_along_heading(region, 0.0);
  const double c = std::cos(30.0 * M_PI / 180.0), s = std::sin(30.0 * M_PI / 180.0);
  const double ellipse_across = std::hypot(15 * s, 5 * c), rectangle_across = 15 * s + 5 * c;
  EXPECT_GT(b.width, ellipse_across);
  EXPECT_LT(b.width, rectangle_across);
  EXPECT_GT(b.length, b.width);
}

TEST(LengthenToCover, TheBoxReachesPastTheOutermostFeatures) {
  const OrientedBox windscreen{100, 100, 5, 6, 0};  // spans u = -3 .. 3
  const OrientedBox b = lengthen_to_cover(windscreen, {{95, 101}, {104, 99}, {100, 100}}, 1.0, 20.0);
  EXPECT_NEAR(b.length, 11.0, 1e-9);  // u = -6 .. 5
  EXPECT_NEAR(b.cx, 99.5, 1e-9);
  EXPECT_NEAR(b.cy, 100.0, 1e-9);
  EXPECT_EQ(b.width, 5.0);
  EXPECT_EQ(b.angle_deg, 0.0);
}

TEST(LengthenToCover, GrowsAlongATiltedAxisAndNoFurtherThanTheCap) {
  const OrientedBox tilted{100, 100, 5, 6, 90};  // its axis points along +y
  const OrientedBox b = lengthen_to_cover(tilted, {{100, 95}, {100, 104}}, 1.0, 8.0);
  // It asked for 3 px at -u and 2 px at +u; the cap allows 2 in all, shared in that proportion.
  EXPECT_NEAR(b.length, 8.0, 1e-9);
  EXPECT_NEAR(b.cy, 100.0 + 0.5 * (-4.2 + 3.8), 1e-9);
  EXPECT_NEAR(b.cx, 100.0, 1e-9);
  // A box already as long as the cap, or points within it, leave it as it is.
  const OrientedBox car{100, 100, 5, 14, 0};
  EXPECT_EQ(lengthen_to_cover(car, {{80, 100}}, 1.0, 13.0).length, 14.0);
  EXPECT_EQ(lengthen_to_cover(car, {{101, 100}}, 1.0, 20.0).cx, 100.0);
}

}  // namespace
}  // namespace uavmot::tracking
