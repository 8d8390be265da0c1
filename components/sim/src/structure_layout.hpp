#pragma once
// Where the static 3-D structures stand: buildings, trees and walls placed from the seed on
// the ground the sequence sees, never on asphalt (roads, parking lots), some right beside a
// road so that they hide passing vehicles at times, and trees whose canopies reach over it.

#include <array>
#include <cstdint>
#include <vector>

#include <opencv2/core/types.hpp>

#include "road_network.hpp"
#include "uavmot/sim/scenario.hpp"
#include "uavmot/sim/simulator.hpp"

namespace uavmot::sim::detail {

struct Structure {
  int id = 0;  // from 1, in placement order
  StructureKind kind = StructureKind::Building;
  cv::Point2d centre_m;      // on the ground
  double angle_rad = 0.0;    // direction of the `length_m` side (buildings, walls)
  double length_m = 0.0;     // buildings and walls: footprint sides
  double width_m = 0.0;
  double height_m = 0.0;     // roof, wall top or top of the canopy
  // Trees: canopy radius and the height of its underside (the trunk ends there).
  double canopy_radius_m = 0.0;
  double canopy_base_m = 0.0;
  uint64_t look_seed = 0;    // texture and colour of this structure

  // Footprint corners counter-clockwise seen from above (x right, y down: the order
  // centre + (+l, +w), (-l, +w), (-l, -w), (+l, -w) in the local frame).
  std::array<cv::Point2d, 4> footprint() const;
};

// Places the structures of `scenario.structures` over `region_m` (world metres).
std::vector<Structure> place_structures(const Scenario& scenario, const RoadNetwork& network, cv::Rect2d region_m,
                                        uint64_t seed);

}  // namespace uavmot::sim::detail
