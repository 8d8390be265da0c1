// The frame's contrast (image_contrast.hpp) and the corner threshold it scales: a ramp gives its
// slope, halving the contrast halves the figure, and the threshold's factor is the contrast ratio
// squared within [contrast_min_scale, 1].

#include "image_contrast.hpp"

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

namespace uavmot::motion {
namespace {

cv::Mat horizontal_ramp(cv::Size size, int slope) {
  cv::Mat image(size, CV_8UC1);
  for (int y = 0; y < size.height; ++y) {
    for (int x = 0; x < size.width; ++x) image.at<uchar>(y, x) = cv::saturate_cast<uchar>(10 + slope * x);
  }
  return image;
}

// Blurred noise around mid-grey at `contrast` (1 = full): edges of every height.
cv::Mat texture(double contrast) {
  cv::RNG rng(11);
  cv::Mat noise(cv::Size(320, 240), CV_32F);
  rng.fill(noise, cv::RNG::NORMAL, 0.0, 60.0);
  cv::Mat blurred, out;
  cv::GaussianBlur(noise, blurred, cv::Size(0, 0), 1.5);
  cv::Mat image = 128.0 + contrast * blurred;
  image.convertTo(out, CV_8U);
  return out;
}

TEST(GradientPercentile, ARampGivesItsSlopeAtEveryPercentile) {
  const cv::Mat ramp = horizontal_ramp(cv::Size(60, 40), 3);  // 10 + 3 x <= 187: no saturation
  EXPECT_DOUBLE_EQ(gradient_percentile(ramp, 50.0, 1), 3.0);
  EXPECT_DOUBLE_EQ(gradient_percentile(ramp, 99.0, 8), 3.0);
  EXPECT_DOUBLE_EQ(gradient_percentile(cv::Mat(40, 60, CV_8UC1, cv::Scalar(90)), 99.0, 1), 0.0);
}

TEST(GradientPercentile, HalvingTheContrastHalvesIt) {
  const double full = gradient_percentile(texture(1.0), 99.0, 8);
  const double half = gradient_percentile(texture(0.5), 99.0, 8);
  ASSERT_GT(full, 10.0);  // enough half-level bins for a 5 % check
  EXPECT_NEAR(half / full, 0.5, 0.05);
}

TEST(GradientPercentile, TooSmallOrNotGreyGivesZero) {
  EXPECT_EQ(gradient_percentile(cv::Mat(), 99.0, 8), 0.0);
  EXPECT_EQ(gradient_percentile(cv::Mat(2, 50, CV_8UC1, cv::Scalar(1)), 99.0, 8), 0.0);
  EXPECT_EQ(gradient_percentile(cv::Mat(40, 60, CV_8UC3, cv::Scalar(1, 2, 3)), 99.0, 8), 0.0);
}

TEST(CornerResponseScale, IsTheSquaredContrastRatioWithinItsBounds) {
  EXPECT_DOUBLE_EQ(corner_response_scale(30.0, 24.0, 0.5), 1.0);   // clear frames keep the threshold
  EXPECT_DOUBLE_EQ(corner_response_scale(24.0, 24.0, 0.5), 1.0);
  EXPECT_NEAR(corner_response_scale(20.0, 24.0, 0.5), (20.0 / 24.0) * (20.0 / 24.0), 1e-12);
  EXPECT_DOUBLE_EQ(corner_response_scale(6.0, 24.0, 0.5), 0.5);    // never below the floor
  EXPECT_DOUBLE_EQ(corner_response_scale(0.0, 24.0, 0.25), 0.25);  // a blank frame
  EXPECT_DOUBLE_EQ(corner_response_scale(6.0, 0.0, 0.5), 1.0);     // off
}

}  // namespace
}  // namespace uavmot::motion
