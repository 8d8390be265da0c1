// When the feature budget is short, new corners go where the image is least covered. At 1080p the
// grid has more cells than max_features; filling cells in row-major order spent each frame's small
// budget on scattered gaps in the top rows while the right and bottom edges, where new ground
// enters the view, stayed empty (almost no tracks at x > 1680 or y > 945).
#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include "grid_corner_detector.hpp"

namespace uavmot::motion {
namespace {

TEST(GridCoverage, AShortBudgetFillsTheEmptyEdgesFirst) {
  const cv::Size size(1920, 1080);
  cv::Mat gray(size, CV_8UC1);
  cv::RNG rng(3);
  rng.fill(gray, cv::RNG::UNIFORM, 0, 256);  // corners everywhere
  MotionOptions o;
  const int cell = detection_cell_size(o, size);
  ASSERT_GT(((size.width + cell - 1) / cell) * ((size.height + cell - 1) / cell), o.max_features);

  // Live features in every cell left of x = 1680 and above y = 945, except every 7th cell (the
  // scattered gaps tracking leaves); nothing in the right and bottom strips.
  std::vector<cv::Point2f> existing;
  int index = 0, gaps = 0;
  for (int y = 0; y + cell <= 945; y += cell)
    for (int x = 0; x + cell <= 1680; x += cell, ++index) {
      if (index % 7 == 0) {
        ++gaps;
        continue;
      }
      existing.emplace_back(static_cast<float>(x + cell / 2), static_cast<float>(y + cell / 2));
    }
  o.max_features = static_cast<int>(existing.size()) + 300;  // budget: 300 new corners
  ASSERT_GT(gaps, 300);  // row-major order would spend the whole budget on the gaps

  const auto added = detect_missing_corners(gray, existing, o);
  ASSERT_EQ(added.size(), 300u);
  int in_strips = 0;
  for (const auto& p : added) in_strips += (p.x >= 1680 || p.y >= 945) ? 1 : 0;
  EXPECT_EQ(in_strips, 300) << "new corners in the empty right/bottom strips";
}

// A cell that gave no corner waits empty_cell_retry_frames frames, unless the camera moves new
// ground into it sooner: at a cell's width per frame (`fastcam`) a 4-frame wait left the vehicles
// entering the view unseen for up to 7 frames.
TEST(GridCoverage, AnEmptyCellIsSearchedAgainOnceTheCameraHasMovedNewGroundIn) {
  const cv::Size size(320, 240);
  const cv::Mat flat(size, CV_8UC1, cv::Scalar(90));
  cv::Mat textured(size, CV_8UC1);
  cv::RNG rng(11);
  rng.fill(textured, cv::RNG::UNIFORM, 0, 256);
  MotionOptions o;
  o.cell_size_px = 40;
  o.empty_cell_retry_frames = 4;
  o.empty_cell_retry_shift_cells = 1.0;
  const Homography still = Homography::eye();
  const Homography fast(1, 0, 36, 0, 1, 30, 0, 0, 1);  // 46.9 px per frame: more than a cell
  const Homography slow(1, 0, 10, 0, 1, 0, 0, 0, 1);   // 10 px per frame: 4 frames for a cell

  const auto corners_next_frame = [&](const Homography& motion, const MotionOptions& options) {
    GridCornerDetector detector(options);
    EXPECT_TRUE(detector.detect(flat, {}, true, 1.0, motion).empty());  // every cell empty, waiting
    return detector.detect(textured, {}, true, 1.0, motion).size();
  };
  EXPECT_EQ(corners_next_frame(still, o), 0u);
  EXPECT_EQ(corners_next_frame(slow, o), 0u);
  EXPECT_EQ(corners_next_frame(fast, o), static_cast<size_t>((320 / 40) * (240 / 40)));
  MotionOptions frames_only = o;
  frames_only.empty_cell_retry_shift_cells = 0.0;
  EXPECT_EQ(corners_next_frame(fast, frames_only), 0u);
}

}  // namespace
}  // namespace uavmot::motion
