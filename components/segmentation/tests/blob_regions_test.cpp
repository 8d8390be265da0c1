#include "uavmot/segmentation/blob_regions.hpp"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "synthetic.hpp"
#include "uavmot/segmentation/gradients.hpp"

namespace uavmot::segmentation {
namespace {

TEST(NormaliseAccumulator, MapsTheMaximumTo255UnlessBelowTheReference) {
  cv::Mat acc = (cv::Mat_<float>(1, 3) << 0.f, 10.f, 40.f);
  const cv::Mat strong = normalise_accumulator(acc, 20.0);
  EXPECT_FLOAT_EQ(strong.at<float>(2), 255.f);
  EXPECT_FLOAT_EQ(strong.at<float>(1), 63.75f);
  const cv::Mat weak = normalise_accumulator(acc, 80.0);  // noise is not stretched
  EXPECT_FLOAT_EQ(weak.at<float>(2), 127.5f);
}

TEST(FuseAccumulators, SumsOrMultipliesPixelwise) {
  const cv::Mat a = (cv::Mat_<float>(1, 2) << 255.f, 100.f);
  const cv::Mat b = (cv::Mat_<float>(1, 2) << 51.f, 0.f);
  const cv::Mat sum = fuse_accumulators({a, b}, FusionRule::Sum);
  EXPECT_FLOAT_EQ(sum.at<float>(0), 306.f);
  EXPECT_FLOAT_EQ(sum.at<float>(1), 100.f);
  const cv::Mat product = fuse_accumulators({a, b}, FusionRule::Product);
  EXPECT_FLOAT_EQ(product.at<float>(0), 51.f);
  EXPECT_FLOAT_EQ(product.at<float>(1), 0.f);
}

TEST(AdaptiveThreshold, IsTheQuantileButAtLeastTheFloor) {
  cv::Mat acc(1, 101, CV_32F);
  for (int i = 0; i <= 100; ++i) acc.at<float>(100 - i) = static_cast<float>(i);
  const double resolution = 100.0 / 4095.0;
  EXPECT_NEAR(adaptive_threshold(acc, 0.8, 0.0), 80.0, resolution);
  EXPECT_NEAR(adaptive_threshold(acc, 0.5, 0.0), 50.0, resolution);
  EXPECT_NEAR(adaptive_threshold(acc, 0.0, 0.0), 0.0, resolution);
  EXPECT_NEAR(adaptive_threshold(acc, 1.0, 0.0), 100.0, resolution);
  EXPECT_DOUBLE_EQ(adaptive_threshold(acc, 0.5, 70.0), 70.0);
  EXPECT_DOUBLE_EQ(adaptive_threshold(cv::Mat::zeros(3, 3, CV_32F), 0.5, 12.0), 12.0);
}

TEST(ExtractBlobs, OutlinesOfTwoNearbyRectanglesStaySeparate) {
  // Two 15 x 5 rectangles with a 4 px gap between them: their gradient rings do not touch,
  // and closing each component alone does not bridge the gap.
  cv::Mat image(40, 60, CV_8U, cv::Scalar(60));
  image(cv::Rect(20, 10, 15, 5)).setTo(cv::Scalar(160));
  image(cv::Rect(20, 19, 15, 5)).setTo(cv::Scalar(160));
  const cv::Mat acc = morphological_gradient(image, {3});
  const auto blobs = extract_blobs(acc, 50.0, 3, 1.0);
  ASSERT_EQ(blobs.size(), 2u);
  // Continuous truth: x in [19.5, 34.5], y in [9.5, 14.5] and [18.5, 23.5].
  EXPECT_NEAR(blobs[0].box.cx, 27.0, 1e-3);
  EXPECT_NEAR(blobs[0].box.cy, 12.0, 1e-3);
  EXPECT_NEAR(blobs[1].box.cy, 21.0, 1e-3);
  for (const auto& b : blobs) {
    EXPECT_NEAR(b.box.length, 15.0, 1e-3);
    EXPECT_NEAR(b.box.width, 5.0, 1e-3);
    EXPECT_NEAR(std::abs(b.box.angle_deg), 0.0, 1e-3);
  }
}

TEST(ExtractBlobs, ClosingFillsTheRingIntoOneBlob) {
  cv::Mat ring = cv::Mat::zeros(30, 30, CV_32F);
  cv::rectangle(ring, cv::Rect(5, 5, 16, 8), cv::Scalar(100), 1);
  ring.at<float>(5, 12) = 0;  // a one-pixel break in the outline
  const auto blobs = extract_blobs(ring, 50.0, 3, 0.0);
  ASSERT_EQ(blobs.size(), 1u);
  EXPECT_NEAR(blobs[0].box.length, 16.0, 1e-3);
  EXPECT_NEAR(blobs[0].box.width, 8.0, 1e-3);
}

TEST(ExtractBlobs, MomentBoxIsUnbiasedOnARotatedRectangle) {
  // A 24 x 8 rectangle at 30 degrees, sampled exactly at pixel centres.
  cv::Mat image = cv::Mat::zeros(60, 60, CV_8U);
  testing::draw_car(image, OrientedBox{30.3, 29.6, 8.0, 24.0, 30.0}, 100);
  cv::Mat acc;
  image.convertTo(acc, CV_32F);
  const auto moments = extract_blobs(acc, 50.0, 1, 0.0, BoxFit::Moments);
  const auto hull = extract_blobs(acc, 50.0, 1, 0.0, BoxFit::MinAreaRect);
  ASSERT_EQ(moments.size(), 1u);
  ASSERT_EQ(hull.size(), 1u);
  EXPECT_NEAR(moments[0].box.cx, 30.3, 0.1);
  EXPECT_NEAR(moments[0].box.cy, 29.6, 0.1);
  EXPECT_NEAR(moments[0].box.length, 24.0, 0.3);
  EXPECT_NEAR(moments[0].box.width, 8.0, 0.3);
  EXPECT_NEAR(moments[0].box.angle_deg, 30.0, 1.0);
  // The hull of the pixel staircase, grown to pixel extent, is larger.
  EXPECT_GT(hull[0].box.length, moments[0].box.length + 0.4);
  EXPECT_NEAR(hull[0].box.angle_deg, 30.0, 3.0);
}

TEST(ExtractBlobs, FourConnectivityKeepsDiagonallyTouchingBlobsApart) {
  cv::Mat acc = cv::Mat::zeros(20, 20, CV_32F);
  acc(cv::Rect(2, 2, 6, 6)).setTo(100);
  acc(cv::Rect(8, 8, 6, 6)).setTo(100);  // touches the first only at a corner
  EXPECT_EQ(extract_blobs(acc, 50.0, 1, 0.0, BoxFit::Moments, 4).size(), 2u);
  EXPECT_EQ(extract_blobs(acc, 50.0, 1, 0.0, BoxFit::Moments, 8).size(), 1u);
}

TEST(ExtractBlobs, NothingAboveThresholdGivesNoBlob) {
  EXPECT_TRUE(extract_blobs(cv::Mat::zeros(20, 20, CV_32F), 10.0, 3, 1.0).empty());
  EXPECT_TRUE(extract_blobs(cv::Mat(), 10.0, 3, 1.0).empty());
}

// A car painted like the road shows only its windows: two bars across the car, a few pixels apart.
std::vector<Blob> two_window_bars(double gap_px) {
  Blob rear, front;
  rear.box = {100.0, 50.0, 2.0, 5.0, 90.0};  // 2 px along the car (x), 5 px across
  front.box = {100.0 + 2.0 + gap_px, 50.0, 2.0, 5.0, 90.0};
  rear.pixel_count = 10;
  front.pixel_count = 9;
  return {rear, front};
}

TEST(GroupVehicleParts, WindowBarsWithinTheTouchDistanceAreOneVehicle) {
  const auto grouped = group_vehicle_parts(two_window_bars(2.5), 16.7, 7.7, 3.0);
  ASSERT_EQ(grouped.size(), 1u);
  EXPECT_EQ(grouped[0].parts, 2);
  EXPECT_NEAR(grouped[0].box.length, 6.5, 0.01);  // rear edge of one bar to front edge of the other
  EXPECT_NEAR(grouped[0].box.width, 5.0, 0.01);
  EXPECT_NEAR(grouped[0].box.cx, 102.25, 0.01);
  EXPECT_EQ(group_vehicle_parts(two_window_bars(2.5), 16.7, 7.7, 1.5).size(), 2u);  // the old 1.5 px
}

TEST(GroupVehicleParts, FartherBlobsOrAGroupLargerThanAVehicleStaySeparate) {
  EXPECT_EQ(group_vehicle_parts(two_window_bars(4.0), 16.7, 7.7, 3.0).size(), 2u);
  EXPECT_EQ(group_vehicle_parts(two_window_bars(2.5), 6.0, 7.7, 3.0).size(), 2u);  // 6.5 px > 6 px
  EXPECT_EQ(group_vehicle_parts(two_window_bars(2.5), 0.0, 0.0, 3.0).size(), 2u);  // disabled
}

}  // namespace
}  // namespace uavmot::segmentation
