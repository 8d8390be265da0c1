#include "creeping_features.hpp"

#include <algorithm>
#include <cmath>

#include "uavmot/core/spatial_grid.hpp"

namespace uavmot::motion {

namespace {

constexpr double kSameWayCosine = 0.5;  // within 60 degrees

}  // namespace

std::vector<unsigned char> creeping_features(const std::vector<cv::Point2f>& positions,
                                             const std::vector<cv::Vec2d>& velocities,
                                             const std::vector<unsigned char>& decidable, const CreepRule& rule) {
  const size_t n = positions.size();
  std::vector<unsigned char> creeping(n, 0);
  if (!(rule.creep_floor_px < rule.floor_px) || !(rule.neighbour_radius_px > 0.0)) return creeping;
  std::vector<double> speed(n, 0.0);
  for (size_t k = 0; k < n; ++k) speed[k] = std::hypot(velocities[k][0], velocities[k][1]);
  const auto point = [&](size_t k) { return cv::Rect2d(positions[k].x, positions[k].y, 0.0, 0.0); };
  // Only features faster than ratio x the creep floor can veto; the candidates give each other
  // support. Cells of one radius (at least a pixel: a tiny radius would make cells without end).
  const double cell = std::max(rule.neighbour_radius_px, 1.0);
  SpatialGrid fast(cell), slow(cell);
  std::vector<size_t> candidates;
  for (size_t k = 0; k < n; ++k) {
    if (!decidable[k]) continue;
    if (speed[k] > rule.neighbour_ratio * rule.creep_floor_px) fast.insert(static_cast<int>(k), point(k));
    if (speed[k] >= rule.creep_floor_px && speed[k] < rule.floor_px) {
      candidates.push_back(k);
      slow.insert(static_cast<int>(k), point(k));
    }
  }
  const double radius2 = rule.neighbour_radius_px * rule.neighbour_radius_px;
  // Whether `stop` returns true for a feature of `grid` within the radius of k (k itself left out).
  const auto any_near = [&](const SpatialGrid& grid, size_t k, const auto& stop) {
    for (const int i : grid.query_near(point(k), rule.neighbour_radius_px)) {
      const auto j = static_cast<size_t>(i);
      if (j == k) continue;
      const double dx = positions[j].x - positions[k].x;
      const double dy = positions[j].y - positions[k].y;
      if (dx * dx + dy * dy <= radius2 && stop(j)) return true;
    }
    return false;
  };
  const auto same_way = [&](size_t j, size_t k) {
    return velocities[j].dot(velocities[k]) > kSameWayCosine * speed[j] * speed[k];
  };
  for (const size_t k : candidates) {
    const bool vetoed = any_near(fast, k, [&](size_t j) { return speed[j] > rule.neighbour_ratio * speed[k] && same_way(j, k); });
    if (vetoed) continue;
    // A creeping car shows more than one corner going its way at its pace; a lone slow corner is noise.
    int support = 1;
    any_near(slow, k, [&](size_t j) {
      if (same_way(j, k) && speed[j] <= rule.neighbour_ratio * speed[k] && speed[k] <= rule.neighbour_ratio * speed[j]) ++support;
      return support >= rule.min_support;
    });
    creeping[k] = support >= rule.min_support ? 1 : 0;
  }
  return creeping;
}

}  // namespace uavmot::motion
