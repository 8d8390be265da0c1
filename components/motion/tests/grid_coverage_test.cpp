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

}  // namespace
}  // namespace uavmot::motion
