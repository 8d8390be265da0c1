#pragma once
// Road geometry on the ground (world metres): densely sampled centrelines with lanes in
// both directions, generated around the camera's path from the scenario and the seed.

#include <cstdint>
#include <vector>

#include <opencv2/core/types.hpp>

#include "uavmot/sim/scenario.hpp"

namespace uavmot::sim::detail {

struct Road {
  std::vector<cv::Point2d> points;  // centreline, about 0.5 m apart
  std::vector<double> arc;          // cumulative length at each point
  std::vector<double> curvature;    // 1/m, unsigned, at each point
  int lanes_per_direction = 1;
  double lane_width_m = 3.5;
  bool main = false;
  bool parking_strip = false;       // a parking strip beyond the outer lane on both sides

  double length() const { return arc.empty() ? 0.0 : arc.back(); }
  double half_width() const { return lanes_per_direction * lane_width_m + (parking_strip ? 2.6 : 0.6); }
  // Centreline point and unit tangent at arc length s (clamped to the road).
  cv::Point2d point_at(double s) const;
  cv::Point2d tangent_at(double s) const;
  double curvature_at(double s) const;
  // Highest curvature in [s, s + ahead] (for slowing down before a bend).
  double max_curvature_ahead(double s, double ahead) const;
};

// Where two roads cross: arc length on each.
struct Crossing {
  int road_a = 0;
  int road_b = 0;
  double s_a = 0.0;
  double s_b = 0.0;
};

// A stall for a parked vehicle.
struct ParkingSpot {
  cv::Point2d centre_m;
  double heading_rad = 0.0;
};

struct RoadNetwork {
  std::vector<Road> roads;  // roads[0] is the main road
  std::vector<Crossing> crossings;
  std::vector<ParkingSpot> parking_spots;
  // Parking lot rectangles (centre, size, angle) drawn as asphalt with stall lines.
  struct Lot {
    cv::Point2d centre_m;
    double along_m = 0.0;
    double across_m = 0.0;
    double angle_rad = 0.0;
  };
  std::vector<Lot> lots;
};

// `centre_m`: the middle of the area the camera sees; `extent_m`: half the diagonal of that area
// plus margin (roads run through and beyond it so vehicles enter and leave the view).
RoadNetwork make_road_network(const Scenario& scenario, cv::Point2d centre_m, double extent_m,
                              double view_radius_m, uint64_t seed);

// Smallest distance from `p` to the road's centreline.
double distance_to_road(const Road& road, cv::Point2d p);

}  // namespace uavmot::sim::detail
