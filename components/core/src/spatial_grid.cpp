#include "uavmot/core/spatial_grid.hpp"

#include <algorithm>
#include <cmath>

namespace uavmot {
namespace {
// Cells per query side beyond which a box is treated as huge and clamped (a corrupt box must not
// make a query walk millions of cells).
constexpr int64_t kMaxCellsPerSide = 64;
}  // namespace

SpatialGrid::SpatialGrid(double cell_size_px) : cell_size_(cell_size_px > 0.0 ? cell_size_px : 32.0) {}

int64_t SpatialGrid::cell(double coordinate) const {
  const double c = std::floor(coordinate / cell_size_);
  return static_cast<int64_t>(std::clamp(c, -1e9, 1e9));
}

void SpatialGrid::insert(int index, const cv::Rect2d& bounds) {
  const int64_t x0 = cell(bounds.x);
  const int64_t y0 = cell(bounds.y);
  const int64_t x1 = std::min(cell(bounds.x + bounds.width), x0 + kMaxCellsPerSide);
  const int64_t y1 = std::min(cell(bounds.y + bounds.height), y0 + kMaxCellsPerSide);
  for (int64_t cy = y0; cy <= y1; ++cy) {
    for (int64_t cx = x0; cx <= x1; ++cx) cells_[key(cx, cy)].push_back(index);
  }
}

std::vector<int> SpatialGrid::query_near(const cv::Rect2d& bounds, double margin) const {
  return query(cv::Rect2d(bounds.x - margin, bounds.y - margin, bounds.width + 2.0 * margin, bounds.height + 2.0 * margin));
}

std::vector<int> SpatialGrid::query(const cv::Rect2d& bounds) const {
  std::vector<int> out;
  const int64_t x0 = cell(bounds.x);
  const int64_t y0 = cell(bounds.y);
  const int64_t x1 = std::min(cell(bounds.x + bounds.width), x0 + kMaxCellsPerSide);
  const int64_t y1 = std::min(cell(bounds.y + bounds.height), y0 + kMaxCellsPerSide);
  for (int64_t cy = y0; cy <= y1; ++cy) {
    for (int64_t cx = x0; cx <= x1; ++cx) {
      const auto it = cells_.find(key(cx, cy));
      if (it != cells_.end()) out.insert(out.end(), it->second.begin(), it->second.end());
    }
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

}  // namespace uavmot
