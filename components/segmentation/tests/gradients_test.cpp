#include "uavmot/segmentation/gradients.hpp"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

namespace uavmot::segmentation {
namespace {

// 60 x 50 background of `background` with a 20 x 10 rectangle of `value` at (20, 20).
cv::Mat rectangle_patch(int background = 50, int value = 150) {
  cv::Mat image(50, 60, CV_8U, cv::Scalar(background));
  image(cv::Rect(20, 20, 20, 10)).setTo(cv::Scalar(value));
  return image;
}

bool on_rectangle_boundary(int x, int y) {
  // The two pixel rings either side of the rectangle's outline.
  const bool inside_outer = x >= 19 && x <= 40 && y >= 19 && y <= 30;
  const bool inside_inner = x >= 21 && x <= 38 && y >= 21 && y <= 28;
  return inside_outer && !inside_inner;
}

// Max of acc over pixels at least `distance` px (chessboard) away from the rectangle outline.
double max_away_from_boundary(const cv::Mat& acc, int distance) {
  double m = 0.0;
  for (int y = 0; y < acc.rows; ++y) {
    for (int x = 0; x < acc.cols; ++x) {
      const int dx = std::max({19 - x, x - 40, 0}), dy = std::max({19 - y, y - 30, 0});
      const bool outside = std::max(dx, dy) >= distance;
      const bool inside = x >= 20 + distance && x <= 39 - distance && y >= 20 + distance && y <= 29 - distance;
      if (outside || inside) m = std::max(m, static_cast<double>(acc.at<float>(y, x)));
    }
  }
  return m;
}

void expect_peak_on_boundary(const cv::Mat& acc) {
  cv::Point peak;
  double max_value = 0.0;
  cv::minMaxLoc(acc, nullptr, &max_value, nullptr, &peak);
  ASSERT_GT(max_value, 0.0);
  EXPECT_TRUE(on_rectangle_boundary(peak.x, peak.y)) << "peak at " << peak;
  // Every boundary pixel beside a straight side (not a corner) responds strongly.
  for (int x = 23; x <= 36; ++x) {
    EXPECT_GT(acc.at<float>(19, x), 0.3 * max_value) << "top edge x=" << x;
    EXPECT_GT(acc.at<float>(20, x), 0.3 * max_value) << "top edge x=" << x;
    EXPECT_GT(acc.at<float>(30, x), 0.3 * max_value) << "bottom edge x=" << x;
  }
}

TEST(KornKernel, PositiveHalfSumsToOneAtEveryScale) {
  for (double sigma : {0.5, 1.0, 2.0, 4.0}) {
    const cv::Mat k = korn_derivative_kernel(sigma);
    const int r = k.rows / 2;
    double positive = 0.0;
    for (int i = 1; i <= r; ++i) {
      positive += k.at<float>(r + i);
      EXPECT_FLOAT_EQ(k.at<float>(r + i), -k.at<float>(r - i));
    }
    EXPECT_NEAR(positive, 1.0, 1e-6) << sigma;
    EXPECT_NEAR(cv::sum(korn_smoothing_kernel(sigma))[0], 1.0, 1e-6);
  }
}

TEST(KornGradient, UnitStepResponseIsScaleIndependent) {
  cv::Mat step(40, 40, CV_8U, cv::Scalar(20));
  step(cv::Rect(20, 0, 20, 40)).setTo(cv::Scalar(120));  // step of 100 between columns 19 and 20
  for (double sigma : {0.7, 1.4, 2.5}) {
    const cv::Mat acc = korn_gradient(step, {sigma});
    EXPECT_NEAR(acc.at<float>(20, 19), 100.0, 0.5) << sigma;
    EXPECT_NEAR(acc.at<float>(20, 20), 100.0, 0.5) << sigma;
    EXPECT_LT(acc.at<float>(20, 5), 1e-3) << sigma;
    EXPECT_LT(acc.at<float>(20, 34), 1e-3) << sigma;
  }
  // Multi-scale: the scales' magnitudes add up.
  EXPECT_NEAR(korn_gradient(step, {0.7, 1.4, 2.5}).at<float>(20, 19), 300.0, 1.5);
}

TEST(KornGradient, RectangleGivesItsBoundaryAndNothingElse) {
  const cv::Mat acc = korn_gradient(rectangle_patch(), {0.7, 1.0});
  expect_peak_on_boundary(acc);
  double max_value = 0.0;
  cv::minMaxLoc(acc, nullptr, &max_value);
  EXPECT_LT(max_away_from_boundary(acc, 4), 0.01 * max_value);
}

TEST(MorphologicalGradient, EqualsHandComputedValuesOnAStep) {
  cv::Mat step(20, 20, CV_8U, cv::Scalar(10));
  step(cv::Rect(10, 0, 10, 20)).setTo(cv::Scalar(110));  // step of 100 between columns 9 and 10
  const cv::Mat acc = morphological_gradient(step, {3, 5});
  // 3x3 reaches across the step from columns 9 and 10, 5x5 from columns 8..11.
  const float expected[] = {0, 0, 100, 200, 200, 100, 0, 0};  // columns 6..13
  for (int i = 0; i < 8; ++i) EXPECT_FLOAT_EQ(acc.at<float>(10, 6 + i), expected[i]) << "column " << 6 + i;
}

TEST(MorphologicalGradient, RectangleGivesItsBoundaryAndNothingElse) {
  const cv::Mat acc = morphological_gradient(rectangle_patch(), {3, 5});
  expect_peak_on_boundary(acc);
  EXPECT_EQ(max_away_from_boundary(acc, 3), 0.0);
}

TEST(LbpRiu2, ClassifiesHandMadePatterns) {
  EXPECT_EQ(lbp_riu2(10, {10, 10, 10, 10, 10, 10, 10, 10}), 8);  // flat: all >= centre
  EXPECT_EQ(lbp_riu2(10, {0, 0, 0, 0, 0, 0, 0, 0}), 0);          // bright spot
  EXPECT_EQ(lbp_riu2(10, {20, 20, 20, 20, 0, 0, 0, 0}), 4);      // straight edge
  EXPECT_EQ(lbp_riu2(10, {20, 20, 0, 0, 0, 0, 0, 0}), 2);        // corner
  EXPECT_EQ(lbp_riu2(10, {0, 0, 20, 20, 20, 0, 0, 0}), 3);       // rotation invariant: any run of ones
  EXPECT_EQ(lbp_riu2(10, {20, 0, 20, 0, 20, 0, 20, 0}), 9);      // non-uniform: P + 1
  EXPECT_EQ(lbp_riu2(10, {20, 20, 0, 0, 20, 20, 0, 0}), 9);      // a line: two runs, non-uniform
  EXPECT_TRUE(is_texture_primitive(4, 8));
  EXPECT_FALSE(is_texture_primitive(0, 8));
  EXPECT_FALSE(is_texture_primitive(8, 8));
  EXPECT_FALSE(is_texture_primitive(9, 8));
}

TEST(LbpGradient, RectangleGivesItsBoundaryAndNothingElse) {
  const cv::Mat acc = lbp_gradient(rectangle_patch(), 8, {1.0, 2.0}, 4.0);
  expect_peak_on_boundary(acc);
  EXPECT_EQ(max_away_from_boundary(acc, 3), 0.0);
}

TEST(LbpGradient, FlatNoiseBelowTheContrastThresholdGivesNothing) {
  cv::Mat noise(60, 60, CV_8U);
  cv::RNG rng(7);
  rng.fill(noise, cv::RNG::UNIFORM, 100, 104);  // values 100..103: neighbour stddev < 2
  EXPECT_EQ(cv::countNonZero(lbp_gradient(noise, 8, {1.0, 2.0}, 4.0)), 0);
  // The same noise passes when the contrast threshold is off: the threshold is what rejects it.
  EXPECT_GT(cv::countNonZero(lbp_gradient(noise, 8, {1.0, 2.0}, 0.0)), 0);
}

double stddev(const std::vector<double>& values) {
  double mean = 0, sq = 0;
  for (double v : values) mean += v / static_cast<double>(values.size());
  for (double v : values) sq += (v - mean) * (v - mean) / static_cast<double>(values.size());
  return std::sqrt(sq);
}

TEST(LbpGradient, MagnitudeIsTheNeighboursStandardDeviationOnBothSidesOfAnEdge) {
  cv::Mat step(20, 20, CV_8U, cv::Scalar(0));
  step(cv::Rect(10, 0, 10, 20)).setTo(cv::Scalar(100));
  const cv::Mat acc = lbp_gradient(step, 8, {1.0}, 1.0);
  // Neighbours counter-clockwise from the right, bilinear at the diagonals (0.707 px).
  // Column 10, centre 100: the three left neighbours are darker (a uniform edge pattern).
  EXPECT_NEAR(acc.at<float>(10, 10), stddev({100, 100, 100, 29.289, 0, 29.289, 100, 100}), 0.05);
  // Column 9, centre 0: Ojala's code is "flat" (all >= 0); its negative sees the edge.
  EXPECT_NEAR(acc.at<float>(10, 9), stddev({100, 70.711, 0, 0, 0, 0, 0, 70.711}), 0.05);
  EXPECT_EQ(acc.at<float>(10, 5), 0.0f);
  EXPECT_EQ(acc.at<float>(10, 15), 0.0f);
}

TEST(Gradients, EmptyImageGivesEmptyAccumulator) {
  EXPECT_TRUE(korn_gradient(cv::Mat(0, 0, CV_8U), {1.0}).empty());
  EXPECT_TRUE(morphological_gradient(cv::Mat(0, 0, CV_8U), {3}).empty());
  EXPECT_TRUE(lbp_gradient(cv::Mat(0, 0, CV_8U), 8, {1.0}, 4.0).empty());
}

}  // namespace
}  // namespace uavmot::segmentation
