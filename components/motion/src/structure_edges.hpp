#pragma once
// Corners on the silhouette of static structure.
//
// Where a roof edge or a tree crown passes over ground texture, the corner a feature tracker locks
// on is made of two layers: the structure's edge, which moves with the structure's parallax, and
// the ground behind it, which does not. The corner slides along the ground's edge, so its velocity
// is off the epipolar line (only its component across the structure's edge is parallax) and the
// plane + parallax test takes it for independent motion. Such corners lie among the structure's
// own features, which the parallax fit found on their epipolar lines (its supporters), and move
// no faster than structure can there. A feature that is not moving yet and is both does not start
// moving; one already moving (a vehicle passing a building) is not touched.

#include <vector>

#include <opencv2/core/matx.hpp>
#include <opencv2/core/types.hpp>

#include "parallax_filter.hpp"
#include "uavmot/motion/motion_options.hpp"

namespace uavmot::motion {

class StructureEdges {
 public:
  // `supporters`: where this frame's parallax fit found structure (ParallaxFilter::supporters()).
  StructureEdges(std::vector<cv::Point2f> supporters, const MotionOptions& options);

  // Whether `independent_velocity` (what the epipolar step left of `sample.velocity`) is what a
  // corner on a structure's silhouette does: at least parallax_edge_min_supporters supporters
  // within parallax_edge_radius_px, and no faster than parallax_edge_speed_factor x the parallax cap.
  bool explains(const ParallaxSample& sample, const cv::Vec2d& independent_velocity) const;

  // The velocity the moving/stationary decision sees: zero for a feature that is not moving yet
  // and that explains() holds for, else `independent_velocity`.
  cv::Vec2d decided_velocity(const ParallaxSample& sample, const cv::Vec2d& independent_velocity, bool moving) const {
    return !moving && explains(sample, independent_velocity) ? cv::Vec2d(0.0, 0.0) : independent_velocity;
  }

 private:
  int supporters_near(const cv::Point2f& p, int enough) const;

  std::vector<cv::Point2f> supporters_;  // sorted by x
  const MotionOptions& options_;
};

}  // namespace uavmot::motion
