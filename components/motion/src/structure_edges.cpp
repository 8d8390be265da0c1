#include "structure_edges.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace uavmot::motion {

StructureEdges::StructureEdges(std::vector<cv::Point2f> supporters, const MotionOptions& options)
    : supporters_(std::move(supporters)), options_(options) {
  std::sort(supporters_.begin(), supporters_.end(), [](const cv::Point2f& a, const cv::Point2f& b) { return a.x < b.x; });
}

int StructureEdges::supporters_near(const cv::Point2f& p, int enough) const {
  const float r = static_cast<float>(options_.parallax_edge_radius_px);
  auto it = std::lower_bound(supporters_.begin(), supporters_.end(), p.x - r,
                             [](const cv::Point2f& s, float x) { return s.x < x; });
  int count = 0;
  for (; it != supporters_.end() && it->x <= p.x + r && count < enough; ++it) {
    if (*it == p) continue;  // the feature itself
    if (std::hypot(it->x - p.x, it->y - p.y) <= r) ++count;
  }
  return count;
}

bool StructureEdges::explains(const ParallaxSample& sample, const cv::Vec2d& independent_velocity) const {
  if (!(options_.parallax_edge_radius_px > 0.0) || supporters_.empty()) return false;
  const double speed = std::hypot(independent_velocity[0], independent_velocity[1]);
  if (!(speed <= options_.parallax_edge_speed_factor * parallax_cap(sample, options_))) return false;
  return supporters_near(sample.position, options_.parallax_edge_min_supporters) >= options_.parallax_edge_min_supporters;
}

}  // namespace uavmot::motion
