// The corner search passes over cells that may_hold_corner() rules out. It must never rule out a
// cell where cv::cornerMinEigenVal reaches the threshold (a corner would be lost, and the results
// would differ from the exhaustive search), and it must rule out plain cells (else it saves nothing).

#include "corner_bound.hpp"

#include <algorithm>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

namespace uavmot::motion {
namespace {

// Ground-like texture: smooth blobs, a few sharp-edged rectangles (corners), sensor noise, all
// scaled by `contrast` around mid-grey so that many cells lie near the threshold.
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

struct Counts {
  int cells = 0, holding = 0, passed_over = 0, lost = 0;
  int near_threshold = 0;  // peak within [0.5, 2] x the threshold, where the bound's margin matters
};

Counts check(const cv::Mat& gray, const MotionOptions& o, int cell_size) {
  cv::Mat eig;
  cv::cornerMinEigenVal(gray, eig, o.corner_block_size, 3);
  Counts c;
  for (int y = 0; y + cell_size <= gray.rows; y += cell_size) {
    for (int x = 0; x + cell_size <= gray.cols; x += cell_size) {
      const cv::Rect cell(x, y, cell_size, cell_size);
      double peak = 0.0;
      cv::minMaxLoc(eig(cell), nullptr, &peak);
      const bool holds = peak >= o.min_corner_response;
      const bool may = may_hold_corner(gray, cell, o);
      ++c.cells;
      c.holding += holds ? 1 : 0;
      c.passed_over += may ? 0 : 1;
      c.lost += holds && !may ? 1 : 0;
      c.near_threshold += peak >= 0.5 * o.min_corner_response && peak <= 2.0 * o.min_corner_response ? 1 : 0;
    }
  }
  return c;
}

TEST(CornerBound, NeverPassesOverACellWhereCornerMinEigenValReachesTheThreshold) {
  int cells = 0, holding = 0, passed_over = 0, near_threshold = 0;
  for (int block : {3, 5, 7}) {
    for (double contrast : {0.1, 0.25, 0.5, 1.0, 2.0}) {
      for (uint64_t seed : {1u, 2u}) {
        MotionOptions o;
        o.corner_block_size = block;
        const cv::Mat gray = textured(cv::Size(320, 240), contrast, seed * 101 + static_cast<uint64_t>(block));
        const Counts c = check(gray, o, 16);
        EXPECT_EQ(c.lost, 0) << "block " << block << ", contrast " << contrast << ", seed " << seed << ": " << c.lost
                             << " of " << c.holding << " cells with a corner passed over";
        cells += c.cells;
        holding += c.holding;
        passed_over += c.passed_over;
        near_threshold += c.near_threshold;
      }
    }
  }
  // The images span the threshold: both kinds of cell occur often, so the test means something.
  EXPECT_GT(holding, cells / 10) << holding << " of " << cells;
  EXPECT_GT(passed_over, cells / 10) << passed_over << " of " << cells;
  EXPECT_GT(near_threshold, cells / 20) << near_threshold << " of " << cells;
}

TEST(CornerBound, PassesOverFlatAndPlainEdgeCellsAndKeepsACorner) {
  MotionOptions o;
  cv::Mat gray(96, 96, CV_8U, cv::Scalar(100));
  cv::rectangle(gray, cv::Point(0, 40), cv::Point(95, 95), cv::Scalar(180), cv::FILLED);  // a straight edge at y = 40
  cv::rectangle(gray, cv::Point(60, 60), cv::Point(95, 95), cv::Scalar(20), cv::FILLED);  // a corner at (60, 60)
  EXPECT_FALSE(may_hold_corner(gray, cv::Rect(8, 8, 16, 16), o)) << "flat";
  EXPECT_FALSE(may_hold_corner(gray, cv::Rect(8, 32, 16, 16), o)) << "a straight edge is no corner";
  EXPECT_TRUE(may_hold_corner(gray, cv::Rect(52, 52, 16, 16), o)) << "the corner";
  EXPECT_TRUE(may_hold_corner(gray, cv::Rect(0, 0, 16, 16), o)) << "at the border there is no bound";
}

}  // namespace
}  // namespace uavmot::motion
