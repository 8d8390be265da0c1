#include <cmath>

#include <gtest/gtest.h>

#include "eval_test_helpers.hpp"

namespace uavmot::eval {
namespace {
using testing::object;

TEST(HomographyErrors, TransferErrorOfAKnownOffset) {
  Sequence s = testing::empty_sequence(4);
  for (int64_t f = 1; f <= 4; ++f) s.homographies[f] = Homography::eye();
  Predictions p;
  p.boxes[1] = {};
  p.homographies[2] = cv::Matx33d(1, 0, 3, 0, 1, 4, 0, 0, 1);  // 5 px everywhere
  p.homographies[3] = Homography::eye();                       // exact
  // frame 4 missing
  const EvaluationResult r = evaluate(s, p);
  ASSERT_TRUE(r.homography.has_value());
  EXPECT_EQ(r.homography->frames, 2);
  EXPECT_EQ(r.homography->missing, 1);
  EXPECT_NEAR(r.homography->mean_px, 2.5, 1e-9);
  EXPECT_NEAR(r.homography->max_px, 5.0, 1e-9);
  EXPECT_NEAR(r.homography->p95_px, 5.0, 1e-9);
  EXPECT_EQ(r.homography->worst_frame, 2);
}

TEST(HomographyErrors, RotationGivesErrorGrowingWithDistanceFromTheCentre) {
  Sequence s = testing::empty_sequence(2);
  s.homographies[2] = Homography::eye();
  Predictions p;
  // A small rotation about the image centre: the error is r * angle, largest at the corners.
  const double a = 0.001, cx = 159.5, cy = 119.5;
  const cv::Matx33d t(1, 0, cx, 0, 1, cy, 0, 0, 1), r(std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a), 0, 0, 0, 1),
      tinv(1, 0, -cx, 0, 1, -cy, 0, 0, 1);
  p.homographies[2] = t * r * tinv;
  const EvaluationResult result = evaluate(s, p);
  EXPECT_GT(result.homography->max_px, result.homography->mean_px);
  // The outermost grid points (cell centres of a 16 x 16 grid) are 150 and 112.5 px from the centre.
  EXPECT_NEAR(result.homography->max_px, 2.0 * std::sin(a / 2) * std::hypot(150.0, 112.5), 1e-6);
}

TEST(FeatureClassification, PrecisionAndRecallFromTheIdMask) {
  Sequence s = testing::empty_sequence(1);
  s.objects[1] = {object(1, 7, 7, 5, 5), object(2, 13.5, 7, 5, 4, 0, false, true)};
  s.id_mask = [](int64_t) {
    cv::Mat mask = cv::Mat::zeros(20, 20, CV_32S);
    mask(cv::Rect(5, 5, 5, 5)).setTo(1);   // moving car, pixels x 5..9
    mask(cv::Rect(12, 5, 4, 5)).setTo(2);  // parked car, pixels x 12..15
    return mask;
  };
  Predictions p;
  p.features[1] = {
      {1, {7, 7}, {1, 0}, true},     // on the moving car, said moving: TP
      {2, {8, 6}, {0, 0}, false},    // on the moving car, said stationary: FN
      {3, {13, 7}, {1, 0}, true},    // on the parked car, said moving: FP
      {4, {2, 2}, {0, 0}, false},    // on the ground, said stationary: TN
      {5, {10.5, 7}, {0, 0}, true},  // 1.5 px from the moving car's last pixel: ambiguous
  };
  const EvaluationResult r = evaluate(s, p);
  ASSERT_TRUE(r.features.has_value());
  EXPECT_EQ(r.features->features, 5);
  EXPECT_EQ(r.features->true_positive, 1);
  EXPECT_EQ(r.features->false_negative, 1);
  EXPECT_EQ(r.features->false_positive, 1);
  EXPECT_EQ(r.features->true_negative, 1);
  EXPECT_EQ(r.features->ambiguous, 1);
  EXPECT_DOUBLE_EQ(r.features->precision(), 0.5);
  EXPECT_DOUBLE_EQ(r.features->recall(), 0.5);
}

TEST(FeatureClassification, FallsBackToBoxesWithoutMasks) {
  Sequence s = testing::empty_sequence(1);
  s.objects[1] = {object(1, 7, 7, 4, 10)};
  Predictions p;
  p.features[1] = {{1, {7, 7}, {1, 0}, true}, {2, {30, 30}, {0, 0}, true}, {3, {12.8, 7}, {0, 0}, false}};
  const EvaluationResult r = evaluate(s, p);
  EXPECT_EQ(r.features->frames_without_mask, 1);
  EXPECT_EQ(r.features->true_positive, 1);
  EXPECT_EQ(r.features->false_positive, 1);
  EXPECT_EQ(r.features->ambiguous, 1);  // 0.8 px beyond the box end
}

}  // namespace
}  // namespace uavmot::eval
