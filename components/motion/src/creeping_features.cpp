#include "creeping_features.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>

namespace uavmot::motion {

namespace {

constexpr double kSameWayCosine = 0.5;  // within 60 degrees

uint64_t cell_key(int cx, int cy) {
  return (static_cast<uint64_t>(static_cast<uint32_t>(cx)) << 32) | static_cast<uint32_t>(cy);
}

using Buckets = std::unordered_map<uint64_t, std::vector<size_t>>;

}  // namespace

std::vector<unsigned char> creeping_features(const std::vector<cv::Point2f>& positions,
                                             const std::vector<cv::Vec2d>& velocities,
                                             const std::vector<unsigned char>& decidable, const CreepRule& rule) {
  const size_t n = positions.size();
  std::vector<unsigned char> creeping(n, 0);
  if (!(rule.creep_floor_px < rule.floor_px) || !(rule.neighbour_radius_px > 0.0)) return creeping;
  std::vector<double> speed(n, 0.0);
  for (size_t k = 0; k < n; ++k) speed[k] = std::hypot(velocities[k][0], velocities[k][1]);
  // Only features faster than ratio x the creep floor can veto: bucket them in cells of one radius
  // (at least a pixel, so that a tiny radius cannot overflow the cell index).
  const double cell = std::max(rule.neighbour_radius_px, 1.0);
  const auto cell_x = [&](size_t k) { return static_cast<int>(std::floor(positions[k].x / cell)); };
  const auto cell_y = [&](size_t k) { return static_cast<int>(std::floor(positions[k].y / cell)); };
  Buckets fast;
  for (size_t k = 0; k < n; ++k) {
    if (decidable[k] && speed[k] > rule.neighbour_ratio * rule.creep_floor_px) fast[cell_key(cell_x(k), cell_y(k))].push_back(k);
  }
  const double radius2 = rule.neighbour_radius_px * rule.neighbour_radius_px;
  // The candidates, bucketed the same way, for the support count.
  Buckets slow;
  std::vector<size_t> candidates;
  for (size_t k = 0; k < n; ++k) {
    if (!decidable[k] || speed[k] < rule.creep_floor_px || speed[k] >= rule.floor_px) continue;
    candidates.push_back(k);
    slow[cell_key(cell_x(k), cell_y(k))].push_back(k);
  }
  // Visits every feature of `buckets` within the radius of k until `stop` returns true.
  const auto any_near = [&](const Buckets& buckets, size_t k, const auto& stop) {
    const int cx = cell_x(k), cy = cell_y(k);
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        const auto bucket = buckets.find(cell_key(cx + dx, cy + dy));
        if (bucket == buckets.end()) continue;
        for (const size_t j : bucket->second) {
          if (j == k) continue;
          const double ddx = positions[j].x - positions[k].x;
          const double ddy = positions[j].y - positions[k].y;
          if (ddx * ddx + ddy * ddy <= radius2 && stop(j)) return true;
        }
      }
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
