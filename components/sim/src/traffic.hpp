#pragma once
// Microscopic traffic on the road network: car following (IDM), lane changes for overtaking,
// convoys, side-by-side pairs, a stop-and-go signal cycle, and parked vehicles that never move.

#include <array>
#include <cstdint>
#include <map>
#include <random>
#include <vector>

#include <opencv2/core/types.hpp>

#include "road_network.hpp"
#include "uavmot/sim/scenario.hpp"
#include "uavmot/sim/simulator.hpp"

namespace uavmot::sim::detail {

// How a vehicle looks from above; gray levels 0..255.
struct VehicleLook {
  double body = 128.0;
  double roof = 128.0;
  double glass = 30.0;
  double cargo = 200.0;  // trucks: the box body
};

struct Vehicle {
  int internal_id = 0;  // unique from 1, in spawn order
  VehicleKind kind = VehicleKind::Car;
  double length_m = 4.5;
  double width_m = 1.8;
  VehicleLook look;
  bool parked = false;
  // Pose on the ground.
  cv::Point2d position_m;
  double heading_rad = 0.0;
  double speed_mps = 0.0;
  cv::Point2d velocity_mps;
  // Road state (not for parked vehicles).
  int road = -1;
  int direction = 1;       // +1 along the road's arc length, -1 against it
  int lane = 0;            // target lane, 0 = outermost
  double lateral_m = 0.0;  // current offset to the right of the centreline, in the direction of travel
  double lane_change_from_m = 0.0;
  double lane_change_t = -1.0;  // progress 0..1 of a lane change; < 0 when not changing
  double s_m = 0.0;        // distance travelled along the lane
  double desired_speed_mps = 10.0;
  // Scripted vehicles (Scenario::scripted): index of the script, -1 for the traffic model's own.
  int script = -1;
  size_t next_lane_change = 0;
};

class Traffic {
 public:
  Traffic(const Scenario& scenario, const RoadNetwork& network, cv::Point2d view_centre_m, double view_radius_m,
          uint64_t seed);

  // Puts the scenario's scripted vehicles on their roads; their script's clock starts now.
  // `image_centre_m`: the ground point at the image centre of frame 1. Throws InputError for a
  // script that names a road or lane the network does not have or starts off its road.
  void add_scripted(cv::Point2d image_centre_m);
  void step(double dt_s);
  double time_s() const { return time_; }
  const std::vector<Vehicle>& vehicles() const { return vehicles_; }  // parked first, then moving by id

 private:
  struct LaneKey {
    int road;
    int direction;
    int lane;
  };
  struct PendingSpawn {
    double time_s;
    double desired_speed_mps;
    bool convoy_member;
  };
  struct LaneState {
    LaneKey key;
    double next_arrival_s = 0.0;
    std::vector<PendingSpawn> pending;
  };

  double lane_offset(const Road& road, int lane) const;
  double road_s(const Vehicle& v) const;  // position along the road's own arc length
  bool red_light(bool major_road) const;
  bool occupies(const Vehicle& other, int lane) const;
  // Gaps (bumper to bumper) to the nearest vehicle ahead / behind vehicles_[i] in `lane`; needs build_index().
  double gap_to_leader(size_t i, int lane, double& leader_speed) const;
  double gap_to_follower(size_t i, int lane) const;
  double spawn_gap(const Vehicle& v, double& leader_speed) const;  // for a vehicle not yet on the road
  void build_index();
  void mark_occupied_junctions();
  double stop_line_gap(const Vehicle& v) const;
  void schedule_arrivals(LaneState& lane);
  void try_spawn(LaneState& lane);
  Vehicle make_vehicle(bool dark_allowed);
  void update_pose(Vehicle& v) const;
  void add_parked(cv::Point2d view_centre_m, double view_radius_m);
  void populate();
  void advance_scripted(Vehicle& v, double dt_s) const;

  const Scenario& scenario_;
  const RoadNetwork& network_;
  std::mt19937_64 rng_;
  std::vector<Vehicle> vehicles_;
  std::vector<LaneState> lanes_;
  std::map<std::pair<int, int>, std::vector<size_t>> groups_;  // (road, direction) -> vehicles sorted by s
  std::vector<size_t> rank_;                                   // position of each vehicle in its group
  std::vector<std::array<bool, 2>> junction_occupied_;          // per crossing: a vehicle of road_a / road_b inside
  int next_id_ = 1;
  double time_ = 0.0;
  double script_start_s_ = 0.0;
};

}  // namespace uavmot::sim::detail
