// Black bands at the image's edges (analogue capture, letterboxing; the aphill FMV has 4-8 px
// columns at both sides and a black bottom row) are not picture: a corner on the band's edge is
// fixed in the image, so under a moving camera it reads as a mover at the border.
#include <cstdio>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "active_picture.hpp"
#include "test_support.hpp"

namespace uavmot::motion {
namespace {

// `image` with black bands painted in (grey 0-3: compression noise), like the aphill FMV's.
cv::Mat with_bands(const cv::Mat& image, int left, int right, int bottom) {
  cv::Mat out = image.clone();
  cv::RNG rng(3);
  cv::Mat noise(out.size(), CV_8UC1);
  rng.fill(noise, cv::RNG::UNIFORM, 0, 4);
  noise.colRange(0, left).copyTo(out.colRange(0, left));
  noise.colRange(out.cols - right, out.cols).copyTo(out.colRange(out.cols - right, out.cols));
  noise.rowRange(out.rows - bottom, out.rows).copyTo(out.rowRange(out.rows - bottom, out.rows));
  return out;
}

TEST(ActivePicture, TheBlackBandsAtTheEdgesAreNotPicture) {
  cv::Mat textured(240, 360, CV_8UC1);
  cv::RNG(5).fill(textured, cv::RNG::UNIFORM, 40, 200);
  const MotionOptions o;
  EXPECT_EQ(active_picture_area(textured, o), cv::Rect(0, 0, 360, 240));
  // The bands, and 2 lines of soft edge past each.
  EXPECT_EQ(active_picture_area(with_bands(textured, 4, 3, 1), o), cv::Rect(6, 0, 349, 237));

  // Dark picture is still picture: night ground at grey 5-30, and one bright pixel in a dark column.
  cv::Mat dark(240, 360, CV_8UC1);
  cv::RNG(6).fill(dark, cv::RNG::UNIFORM, 5, 30);
  EXPECT_EQ(active_picture_area(dark, o), cv::Rect(0, 0, 360, 240));
  cv::Mat lit = with_bands(textured, 4, 3, 1);
  lit.at<uchar>(100, 1) = 200;
  EXPECT_EQ(active_picture_area(lit, o).x, 3);

  // A black frame: at most an eighth of each side is band. Off: the whole image.
  EXPECT_EQ(active_picture_area(cv::Mat(240, 360, CV_8UC1, cv::Scalar(0)), o), cv::Rect(47, 32, 266, 176));
  MotionOptions off;
  off.blank_band_max_grey = 0.0;
  EXPECT_EQ(active_picture_area(with_bands(textured, 4, 3, 1), off), cv::Rect(0, 0, 360, 240));
  EXPECT_EQ(usable_area(cv::Rect(4, 0, 353, 239), 6), cv::Rect(10, 6, 341, 227));
  EXPECT_TRUE(usable_area(cv::Rect(0, 0, 10, 10), 6).empty());
}

// A camera moving over static ground behind fixed black bands: nothing moves, and no feature
// may say so. Without the bands found, the corners on their inner edges are classified moving.
TEST(ActivePicture, NoFeatureOnABandsEdgeMoves) {
  testing::WarpedSequence sequence(test::camera(3.0, 0.0, {480, 320}));
  const auto moving_near_edges = [&](const MotionOptions& options) {
    MotionEstimator estimator(options);
    int moving = 0, near_edges = 0;
    for (int k = 1; k <= 30; ++k) {
      const auto estimate = estimator.process(test::make_frame(with_bands(sequence.frame(k), 5, 4, 1), k));
      for (const auto& f : estimate.features) {
        if (f.position.x > 30.0 && f.position.x < 450.0) continue;
        ++near_edges;
        moving += f.moving ? 1 : 0;
      }
    }
    EXPECT_GT(near_edges, 100);
    return moving;
  };
  const int with_bands_found = moving_near_edges(MotionOptions{});
  MotionOptions off;
  off.blank_band_max_grey = 0.0;
  const int without = moving_near_edges(off);
  std::printf("moving feature-frames within 30 px of the sides: %d, without the bands found %d\n", with_bands_found, without);
  EXPECT_EQ(with_bands_found, 0);
  EXPECT_GT(without, 0) << "the bands' edges no longer fool the classifier: this test proves nothing";
}

}  // namespace
}  // namespace uavmot::motion
