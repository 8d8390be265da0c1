// The uniform grid behind the tracker's associations and the motion layer's neighbour tests.
#include <gtest/gtest.h>

#include "uavmot/core/spatial_grid.hpp"

namespace uavmot {
namespace {

TEST(SpatialGrid, FindsWhatSharesACellSortedAndOnce) {
  SpatialGrid grid(10.0);
  grid.insert(3, cv::Rect2d(2, 2, 30, 4));   // a long box over four cells
  grid.insert(1, cv::Rect2d(5, 5, 0, 0));    // a point
  grid.insert(2, cv::Rect2d(55, 5, 0, 0));   // far away
  grid.insert(4, cv::Rect2d(-7, -3, 0, 0));  // left of and above the origin
  EXPECT_EQ(grid.query(cv::Rect2d(0, 0, 9, 9)), (std::vector<int>{1, 3}));
  EXPECT_EQ(grid.query(cv::Rect2d(25, 1, 1, 1)), (std::vector<int>{3}));  // the long box, once
  EXPECT_TRUE(grid.query(cv::Rect2d(100, 100, 1, 1)).empty());
  // Grown by a margin of one cell, a point query reaches the neighbouring cells too.
  EXPECT_EQ(grid.query_near(cv::Rect2d(1, 1, 0, 0), 10.0), (std::vector<int>{1, 3, 4}));
}

// Callers pass finite bounds only (the tracker drops non-finite regions first).
TEST(SpatialGrid, AHugeBoxDoesNotWalkWithoutEnd) {
  SpatialGrid grid(1.0);
  grid.insert(0, cv::Rect2d(0, 0, 0, 0));
  grid.insert(1, cv::Rect2d(0, 0, 1e12, 1e12));  // clamped to a bounded number of cells
  EXPECT_EQ(grid.query(cv::Rect2d(0, 0, 1e12, 1e12)), (std::vector<int>{0, 1}));
  EXPECT_EQ(grid.query(cv::Rect2d(0, 0, 0, 0)), (std::vector<int>{0, 1}));
}

}  // namespace
}  // namespace uavmot
