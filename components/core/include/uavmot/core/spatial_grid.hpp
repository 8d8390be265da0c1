#pragma once
// A uniform grid over axis-aligned bounds (boxes, or points as empty boxes), so that finding what lies
// near a box or point costs O(1) on average: the tracker's associations and the motion layer's
// neighbour tests grow linearly with the number of objects. Query results are sorted, so nothing
// depends on hash order.

#include <cstdint>
#include <unordered_map>
#include <vector>

#include <opencv2/core/types.hpp>

namespace uavmot {

class SpatialGrid {
 public:
  explicit SpatialGrid(double cell_size_px = 32.0);

  void insert(int index, const cv::Rect2d& bounds);
  // Indices whose bounds share a cell with `bounds`, ascending, without repeats.
  std::vector<int> query(const cv::Rect2d& bounds) const;
  // The same for `bounds` grown by `margin` on every side (neighbours within that reach).
  std::vector<int> query_near(const cv::Rect2d& bounds, double margin) const;

 private:
  int64_t cell(double coordinate) const;
  static int64_t key(int64_t cx, int64_t cy) { return (cx << 32) ^ (cy & 0xffffffffLL); }

  double cell_size_;
  std::unordered_map<int64_t, std::vector<int>> cells_;
};

}  // namespace uavmot
