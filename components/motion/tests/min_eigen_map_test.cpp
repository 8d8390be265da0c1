// The exact corner response (min_eigen_map.hpp): what cv::cornerMinEigenVal computes, up to its
// float rounding, borders included; the same bits for a pixel whatever region it is computed in;
// and no response on flat ground or a straight edge.

#include "min_eigen_map.hpp"

#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

namespace uavmot::motion {
namespace {

// Ground-like texture: smooth blobs, a few sharp-edged rectangles (corners), sensor noise, all
// scaled by `contrast` around mid-grey so that many pixels lie near the threshold.
cv::Mat textured(cv::Size size, double contrast, uint64_t seed) {
  cv::RNG rng(seed);
  cv::Mat noise(size, CV_32F);
  rng.fill(noise, cv::RNG::NORMAL, 0.0, 40.0);
  cv::Mat blobs;
  cv::GaussianBlur(noise, blobs, cv::Size(0, 0), 4.0);
  for (int i = 0; i < 300; ++i) {
    const cv::Point a(rng.uniform(0, size.width), rng.uniform(0, size.height));
    const cv::Point b = a + cv::Point(rng.uniform(3, 20), rng.uniform(3, 12));
    cv::rectangle(blobs, a, b, cv::Scalar(rng.uniform(-60.0, 60.0)), cv::FILLED);
  }
  cv::Mat fine(size, CV_32F);
  rng.fill(fine, cv::RNG::NORMAL, 0.0, 2.0);
  cv::Mat image = 128.0 + contrast * blobs + fine, out;
  image.convertTo(out, CV_8U);
  return out;
}

cv::Mat whole(const cv::Mat& gray, int block, double floor) {
  cv::Mat out;
  min_eigen_values(gray, cv::Rect(0, 0, gray.cols, gray.rows), block, floor, out);
  return out;
}

TEST(MinEigenMap, AgreesWithCornerMinEigenValUpToItsFloatRounding) {
  for (int block : {3, 5, 7, 15}) {
    for (double contrast : {0.25, 1.0, 2.0}) {
      const cv::Mat gray = textured(cv::Size(200, 150), contrast, static_cast<uint64_t>(block) * 7 + 1);
      const cv::Mat exact = whole(gray, block, 0.0);
      cv::Mat opencv;
      cv::cornerMinEigenVal(gray, opencv, block, 3);
      // OpenCV's float sums and root lose a few ulps of the trace (at most about 1 in these
      // units), which near a straight edge is much of the small eigenvalue: hence an absolute
      // margin, 1 % of the default threshold.
      double worst = 0.0;
      for (int y = 0; y < gray.rows; ++y) {
        for (int x = 0; x < gray.cols; ++x) {
          const double a = exact.at<float>(y, x), b = opencv.at<float>(y, x);
          worst = std::max(worst, std::abs(a - b) - 1e-4 * std::abs(b));
        }
      }
      EXPECT_LT(worst, 2e-5) << "block " << block << ", contrast " << contrast << " (borders included)";
    }
  }
}

TEST(MinEigenMap, APixelHasTheSameBitsInEveryRegionThatHoldsIt) {
  const cv::Mat gray = textured(cv::Size(160, 120), 1.0, 3);
  for (int block : {3, 5, 9}) {
    const double floor = 2e-3;
    const cv::Mat full = whole(gray, block, floor);
    cv::RNG rng(static_cast<uint64_t>(block));
    for (int k = 0; k < 300; ++k) {
      // Regions anywhere, touching the borders too, where the reflection must match the whole image's.
      const int x = rng.uniform(0, gray.cols - 1), y = rng.uniform(0, gray.rows - 1);
      const cv::Rect region =
          cv::Rect(x, y, rng.uniform(1, 40), rng.uniform(1, 40)) & cv::Rect(0, 0, gray.cols, gray.rows);
      cv::Mat part;
      min_eigen_values(gray, region, block, floor, part);
      ASSERT_EQ(cv::norm(part, full(region), cv::NORM_INF), 0.0) << "block " << block << ", region " << region;
    }
  }
}

TEST(MinEigenMap, ValuesThatCannotReachTheFloorAreZeroAndTheRestExact) {
  const cv::Mat gray = textured(cv::Size(160, 120), 0.5, 5);
  const double floor = 2e-3;
  const cv::Mat exact = whole(gray, 5, 0.0), floored = whole(gray, 5, floor);
  int zeroed = 0, kept = 0;
  for (int y = 0; y < gray.rows; ++y) {
    for (int x = 0; x < gray.cols; ++x) {
      const float e = exact.at<float>(y, x), f = floored.at<float>(y, x);
      if (e < floor) {
        ASSERT_EQ(f, 0.0f) << x << "," << y;
        ++zeroed;
      } else {
        ASSERT_EQ(f, e) << x << "," << y;
        ++kept;
      }
    }
  }
  EXPECT_GT(zeroed, 100);  // the image spans the floor, so both cases are tested
  EXPECT_GT(kept, 100);
}

TEST(MinEigenMap, AFlatAreaAndAStraightEdgeGiveNoResponseACornerDoes) {
  cv::Mat gray(96, 96, CV_8U, cv::Scalar(100));
  cv::rectangle(gray, cv::Point(0, 40), cv::Point(95, 95), cv::Scalar(180), cv::FILLED);  // a straight edge at y = 40
  cv::rectangle(gray, cv::Point(60, 60), cv::Point(95, 95), cv::Scalar(20), cv::FILLED);  // a corner at (60, 60)
  const cv::Mat map = whole(gray, 5, 2e-3);
  double flat = 0.0, edge = 0.0, corner = 0.0;
  cv::minMaxLoc(map(cv::Rect(8, 8, 16, 16)), nullptr, &flat);
  cv::minMaxLoc(map(cv::Rect(8, 32, 16, 16)), nullptr, &edge);
  cv::minMaxLoc(map(cv::Rect(52, 52, 16, 16)), nullptr, &corner);
  EXPECT_EQ(flat, 0.0);
  EXPECT_EQ(edge, 0.0) << "a straight edge is no corner";
  EXPECT_GT(corner, 2e-3);
}

}  // namespace
}  // namespace uavmot::motion
