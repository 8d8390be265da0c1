#include "traffic.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "uavmot/core/error.hpp"

namespace uavmot::sim::detail {
namespace {
constexpr double kPi = 3.14159265358979323846;
// Intelligent Driver Model parameters (Treiber et al.), typical urban values.
constexpr double kMaxAccel = 1.2;      // m/s^2
constexpr double kComfortDecel = 2.0;  // m/s^2
constexpr double kMinGap = 2.0;        // m
constexpr double kHeadway = 1.3;       // s
constexpr double kLateralAccel = 2.0;  // m/s^2 allowed in bends
constexpr double kLaneChangeDuration = 3.5;  // s

// Piecewise linear through the keys, held before the first and after the last.
double scripted_speed(const std::vector<SpeedKey>& keys, double t) {
  if (t <= keys.front().at_s) return keys.front().mps;
  for (size_t k = 1; k < keys.size(); ++k) {
    if (t <= keys[k].at_s) {
      const double f = (t - keys[k - 1].at_s) / (keys[k].at_s - keys[k - 1].at_s);
      return keys[k - 1].mps + f * (keys[k].mps - keys[k - 1].mps);
    }
  }
  return keys.back().mps;
}

VehicleKind kind_named(const std::string& name) {
  return name == "truck" ? VehicleKind::Truck : name == "van" ? VehicleKind::Van : VehicleKind::Car;
}

double smoothstep(double x) {
  x = std::clamp(x, 0.0, 1.0);
  return x * x * (3.0 - 2.0 * x);
}
}  // namespace

Traffic::Traffic(const Scenario& scenario, const RoadNetwork& network, cv::Point2d view_centre, double view_radius,
                 uint64_t seed)
    : scenario_(scenario), network_(network), rng_(seed ^ 0x7AFF1CULL) {
  add_parked(view_centre, view_radius);
  for (size_t r = 0; r < network_.roads.size(); ++r) {
    for (int dir : {1, -1}) {
      for (int lane = 0; lane < network_.roads[r].lanes_per_direction; ++lane) {
        LaneState state;
        state.key = {static_cast<int>(r), dir, lane};
        schedule_arrivals(state);
        lanes_.push_back(state);
      }
    }
  }
  populate();
}

void Traffic::populate() {
  // Roads start filled at the mean density (flow / speed), so long roads need no long warm-up.
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  const TrafficParams& t = scenario_.traffic;
  for (const LaneState& lane : lanes_) {
    const Road& road = network_.roads[lane.key.road];
    const double factor = road.main ? 1.0 : t.side_road_speed_factor;
    const double flow = t.flow_per_lane_vph / 3600.0 * (road.main ? 1.0 : 0.6);
    const double mean_speed = std::max(0.5, 0.5 * (t.speed_min_mps + t.speed_max_mps) * factor);
    if (flow <= 0.0) continue;
    std::exponential_distribution<double> gap(flow / mean_speed);
    double last_front = road.length();  // rear end of the vehicle placed ahead
    for (double s = road.length() - 10.0 - gap(rng_); s > 10.0; s -= gap(rng_)) {
      Vehicle v = make_vehicle(true);
      v.desired_speed_mps = (t.speed_min_mps + (t.speed_max_mps - t.speed_min_mps) * uni(rng_)) * factor;
      v.speed_mps = v.desired_speed_mps;
      v.road = lane.key.road;
      v.direction = lane.key.direction;
      v.lane = lane.key.lane;
      v.lateral_m = lane_offset(road, v.lane);
      v.s_m = s;
      if (s + v.length_m / 2.0 + kMinGap + kHeadway * v.speed_mps > last_front) continue;
      last_front = s - v.length_m / 2.0;
      update_pose(v);
      vehicles_.push_back(v);
    }
  }
}

Vehicle Traffic::make_vehicle(bool dark_allowed) {
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  const TrafficParams& t = scenario_.traffic;
  Vehicle v;
  v.internal_id = next_id_++;
  const double kind = uni(rng_);
  if (kind < t.truck_fraction) {
    v.kind = VehicleKind::Truck;
    v.length_m = 8.0 + 4.0 * uni(rng_);
    v.width_m = 2.45 + 0.1 * uni(rng_);
  } else if (kind < t.truck_fraction + t.van_fraction) {
    v.kind = VehicleKind::Van;
    v.length_m = 5.0 + 0.7 * uni(rng_);
    v.width_m = 1.95 + 0.1 * uni(rng_);
  } else {
    v.kind = VehicleKind::Car;
    v.length_m = 4.2 + 0.7 * uni(rng_);
    v.width_m = 1.72 + 0.14 * uni(rng_);
  }
  v.length_m *= t.vehicle_size_scale;
  v.width_m *= t.vehicle_size_scale;
  // Luminance of common car paints: white, silver, gray, red, blue, green; dark ones near asphalt.
  static const double bright[] = {232, 214, 188, 165, 140, 112, 98, 120};
  static const double dark[] = {26, 36, 48, 60, 72};
  const bool is_dark = dark_allowed && uni(rng_) < t.dark_fraction;
  const double base = is_dark ? dark[static_cast<size_t>(uni(rng_) * 5) % 5] : bright[static_cast<size_t>(uni(rng_) * 8) % 8];
  v.look.body = std::clamp(base + 8.0 * (uni(rng_) - 0.5), 0.0, 255.0);
  v.look.roof = std::clamp(v.look.body + (is_dark ? 6.0 : -10.0) * uni(rng_), 0.0, 255.0);
  v.look.glass = 22.0 + 22.0 * uni(rng_);
  v.look.cargo = uni(rng_) < 0.7 ? 200.0 + 35.0 * uni(rng_) : 110.0 + 40.0 * uni(rng_);
  return v;
}

void Traffic::add_parked(cv::Point2d view_centre, double view_radius) {
  std::vector<ParkingSpot> spots;
  for (const ParkingSpot& spot : network_.parking_spots)
    if (cv::norm(spot.centre_m - view_centre) < view_radius) spots.push_back(spot);
  std::shuffle(spots.begin(), spots.end(), rng_);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  const int count = std::min<int>(scenario_.traffic.parked_vehicles, static_cast<int>(spots.size()));
  for (int i = 0; i < count; ++i) {
    Vehicle v = make_vehicle(true);
    if (v.kind == VehicleKind::Truck) {  // no trucks in stalls
      v.kind = VehicleKind::Van;
      v.length_m = 5.2 * scenario_.traffic.vehicle_size_scale;
      v.width_m = 2.0 * scenario_.traffic.vehicle_size_scale;
    }
    v.parked = true;
    v.position_m = spots[i].centre_m + cv::Point2d(0.3 * (uni(rng_) - 0.5), 0.3 * (uni(rng_) - 0.5));
    v.heading_rad = spots[i].heading_rad + (uni(rng_) - 0.5) * 6.0 * kPi / 180.0;
    vehicles_.push_back(v);
  }
}

void Traffic::add_scripted(cv::Point2d image_centre_m) {
  script_start_s_ = time_;
  for (size_t i = 0; i < scenario_.scripted.size(); ++i) {
    const ScriptedVehicle& script = scenario_.scripted[i];
    const std::string name = "scripted[" + std::to_string(i) + "]";
    if (script.road >= static_cast<int>(network_.roads.size()))
      throw InputError(name + ".road " + std::to_string(script.road) + ": the road network has " +
                       std::to_string(network_.roads.size()) + " roads (0 = main)");
    const Road& road = network_.roads[script.road];
    auto check_lane = [&](int lane, const std::string& key) {
      if (lane >= road.lanes_per_direction)
        throw InputError(name + key + " " + std::to_string(lane) + ": road " + std::to_string(script.road) + " has " +
                         std::to_string(road.lanes_per_direction) + " lane(s) per direction");
    };
    check_lane(script.lane, ".lane");
    for (size_t k = 0; k < script.lane_changes.size(); ++k)
      check_lane(script.lane_changes[k].lane, ".lane_changes[" + std::to_string(k) + "].lane");
    // Arc length, in this vehicle's direction of travel, of the centreline point nearest the image centre.
    size_t nearest = 0;
    double nearest_m = cv::norm(road.points[0] - image_centre_m);
    for (size_t p = 1; p < road.points.size(); ++p) {
      const double d = cv::norm(road.points[p] - image_centre_m);
      if (d < nearest_m) {
        nearest_m = d;
        nearest = p;
      }
    }
    const double centre_s = script.direction > 0 ? road.arc[nearest] : road.length() - road.arc[nearest];
    Vehicle v;
    v.internal_id = next_id_++;
    v.script = static_cast<int>(i);
    v.kind = kind_named(script.kind);
    v.length_m = script.length_m;
    v.width_m = script.width_m;
    v.look.body = script.gray;
    v.look.roof = std::clamp(script.gray - 10.0, 0.0, 255.0);
    v.look.glass = 30.0;
    v.look.cargo = std::clamp(script.gray + 15.0, 0.0, 255.0);
    v.road = script.road;
    v.direction = script.direction;
    v.lane = script.lane;
    v.lateral_m = lane_offset(road, v.lane);
    v.s_m = centre_s + script.start_m;
    if (v.s_m < v.length_m / 2.0 || v.s_m > road.length() - v.length_m / 2.0)
      throw InputError(name + ".start_m " + std::to_string(script.start_m) + " is off its road (it runs " +
                       std::to_string(-centre_s) + " to " + std::to_string(road.length() - centre_s) +
                       " m from the image centre)");
    v.speed_mps = v.desired_speed_mps = scripted_speed(script.speed, 0.0);
    update_pose(v);
    vehicles_.push_back(v);
  }
}

void Traffic::advance_scripted(Vehicle& v, double dt) const {
  const ScriptedVehicle& script = scenario_.scripted[static_cast<size_t>(v.script)];
  const double t = time_ - script_start_s_;
  // Lane changes begin at their time; the lateral motion is the traffic model's (in step()).
  if (v.next_lane_change < script.lane_changes.size() && t >= script.lane_changes[v.next_lane_change].at_s) {
    const int lane = script.lane_changes[v.next_lane_change].lane;  // checked against the road in add_scripted()
    ++v.next_lane_change;
    if (lane != v.lane) {
      v.lane_change_from_m = v.lateral_m;
      v.lane = lane;
      v.lane_change_t = 0.0;
    }
  }
  const double new_speed = scripted_speed(script.speed, t + dt);
  v.s_m += 0.5 * (v.speed_mps + new_speed) * dt;
  v.speed_mps = v.desired_speed_mps = new_speed;
}

void Traffic::schedule_arrivals(LaneState& lane) {
  const Road& road = network_.roads[lane.key.road];
  double flow = scenario_.traffic.flow_per_lane_vph / 3600.0;
  if (!road.main) flow *= 0.6;
  if (flow <= 0.0) {
    lane.next_arrival_s = 1e300;
    return;
  }
  std::exponential_distribution<double> gap(flow);
  lane.next_arrival_s = time_ + gap(rng_);
}

double Traffic::lane_offset(const Road& road, int lane) const {
  return (road.lanes_per_direction - lane - 0.5) * road.lane_width_m;
}

double Traffic::road_s(const Vehicle& v) const {
  const Road& road = network_.roads[v.road];
  return v.direction > 0 ? v.s_m : road.length() - v.s_m;
}

bool Traffic::red_light(bool major) const {
  const TrafficParams& t = scenario_.traffic;
  if (t.stop_red_s <= 0.0) return false;
  const double phase = std::fmod(time_, t.stop_period_s);
  if (major) return phase < t.stop_red_s;
  // The minor road gets green only inside the major road's red phase, with clearance at both ends.
  const double clearance = std::min(3.0, 0.25 * t.stop_red_s);
  return !(phase >= clearance && phase < t.stop_red_s - clearance);
}

double Traffic::stop_line_gap(const Vehicle& v) const {
  const Road& road = network_.roads[v.road];
  double best = 1e300;
  // Every crossing has a signal; the road listed first (the main road where it takes part) is the major one.
  for (const Crossing& x : network_.crossings) {
    double s_cross = 0.0;
    int other = -1;
    bool major = false;
    if (x.road_a == v.road) {
      s_cross = x.s_a;
      other = x.road_b;
      major = true;
    } else if (x.road_b == v.road) {
      s_cross = x.s_b;
      other = x.road_a;
    } else {
      continue;
    }
    // Stop for red, and also while a vehicle of the other road is still inside the junction.
    const size_t c = static_cast<size_t>(&x - network_.crossings.data());
    const bool other_inside = junction_occupied_[c][major ? 1 : 0];
    if (!red_light(major) && !other_inside) continue;
    const double lane_s = v.direction > 0 ? s_cross : road.length() - s_cross;
    const double stop = lane_s - network_.roads[other].half_width() - 2.5;
    const double gap = stop - (v.s_m + v.length_m / 2.0);
    // A vehicle that can no longer stop comfortably drives through.
    const double braking = v.speed_mps * v.speed_mps / (2.0 * 4.0);
    if (gap > -0.5 && (gap + 0.5 >= braking || other_inside)) best = std::min(best, std::max(0.0, gap));
  }
  return best;
}

bool Traffic::occupies(const Vehicle& o, int lane) const {
  const Road& road = network_.roads[o.road];
  return o.lane == lane || std::abs(o.lateral_m - lane_offset(road, lane)) < 0.9 * road.lane_width_m;
}

double Traffic::spawn_gap(const Vehicle& v, double& leader_speed) const {
  double best = 1e300;
  leader_speed = 0.0;
  for (const Vehicle& o : vehicles_) {
    if (o.parked || o.road != v.road || o.direction != v.direction || o.s_m <= v.s_m || !occupies(o, v.lane)) continue;
    const double gap = o.s_m - v.s_m - (o.length_m + v.length_m) / 2.0;
    if (gap < best) {
      best = gap;
      leader_speed = o.speed_mps;
    }
  }
  return best;
}

void Traffic::mark_occupied_junctions() {
  junction_occupied_.assign(network_.crossings.size(), {false, false});
  for (const Vehicle& u : vehicles_) {
    if (u.parked) continue;
    for (size_t c = 0; c < network_.crossings.size(); ++c) {
      const Crossing& x = network_.crossings[c];
      if (u.road != x.road_a && u.road != x.road_b) continue;
      const bool on_a = u.road == x.road_a;
      const double s_cross = on_a ? x.s_a : x.s_b;
      const double other_half = network_.roads[on_a ? x.road_b : x.road_a].half_width();
      if (std::abs(road_s(u) - s_cross) < other_half + u.length_m / 2.0 + 1.5) junction_occupied_[c][on_a ? 0 : 1] = true;
    }
  }
}

void Traffic::build_index() {
  groups_.clear();
  rank_.assign(vehicles_.size(), 0);
  for (size_t i = 0; i < vehicles_.size(); ++i)
    if (!vehicles_[i].parked) groups_[{vehicles_[i].road, vehicles_[i].direction}].push_back(i);
  for (auto& [key, members] : groups_) {
    std::sort(members.begin(), members.end(), [&](size_t x, size_t y) {
      const Vehicle& a = vehicles_[x];
      const Vehicle& b = vehicles_[y];
      return a.s_m != b.s_m ? a.s_m < b.s_m : a.internal_id < b.internal_id;
    });
    for (size_t k = 0; k < members.size(); ++k) rank_[members[k]] = k;
  }
}

double Traffic::gap_to_leader(size_t i, int lane, double& leader_speed) const {
  const Vehicle& v = vehicles_[i];
  const auto& members = groups_.at({v.road, v.direction});
  leader_speed = 0.0;
  // Sorted by position: the first vehicle ahead that occupies the lane is the leader.
  for (size_t k = rank_[i] + 1; k < members.size(); ++k) {
    const Vehicle& o = vehicles_[members[k]];
    if (o.s_m <= v.s_m || !occupies(o, lane)) continue;
    leader_speed = o.speed_mps;
    return o.s_m - v.s_m - (o.length_m + v.length_m) / 2.0;
  }
  return 1e300;
}

double Traffic::gap_to_follower(size_t i, int lane) const {
  const Vehicle& v = vehicles_[i];
  const auto& members = groups_.at({v.road, v.direction});
  double best = 1e300;
  // Vehicles level with this one (same position, sorted after it) count as followers too.
  for (size_t k = rank_[i] + 1; k < members.size() && vehicles_[members[k]].s_m == v.s_m; ++k)
    if (occupies(vehicles_[members[k]], lane)) best = std::min(best, -(vehicles_[members[k]].length_m + v.length_m) / 2.0);
  for (size_t k = rank_[i]; k-- > 0;) {
    const Vehicle& o = vehicles_[members[k]];
    if (!occupies(o, lane)) continue;
    return std::min(best, v.s_m - o.s_m - (o.length_m + v.length_m) / 2.0);
  }
  return best;
}

void Traffic::try_spawn(LaneState& lane) {
  if (lane.pending.empty() || lane.pending.front().time_s > time_) return;
  const Road& road = network_.roads[lane.key.road];
  const PendingSpawn spawn = lane.pending.front();
  Vehicle v = make_vehicle(true);
  v.road = lane.key.road;
  v.direction = lane.key.direction;
  v.lane = lane.key.lane;
  v.lateral_m = lane_offset(road, v.lane);
  v.s_m = v.length_m / 2.0;
  v.desired_speed_mps = spawn.desired_speed_mps;
  double leader_speed = 0.0;
  const double gap = spawn_gap(v, leader_speed);
  const double headway = spawn.convoy_member ? 0.9 : kHeadway;
  if (gap < kMinGap + headway * std::min(v.desired_speed_mps, leader_speed + 2.0)) {
    --next_id_;  // not spawned yet: keep ids contiguous
    return;
  }
  v.speed_mps = std::min(v.desired_speed_mps, gap < 60.0 ? leader_speed : v.desired_speed_mps);
  lane.pending.erase(lane.pending.begin());
  update_pose(v);
  vehicles_.push_back(v);
}

void Traffic::update_pose(Vehicle& v) const {
  if (v.parked) return;
  const Road& road = network_.roads[v.road];
  const double s = road_s(v);
  cv::Point2d tangent = road.tangent_at(s) * static_cast<double>(v.direction);
  const cv::Point2d right(-tangent.y, tangent.x);
  v.position_m = road.point_at(s) + right * v.lateral_m;
  double heading = std::atan2(tangent.y, tangent.x);
  if (v.lane_change_t >= 0.0 && v.speed_mps > 0.1) {
    // Heading follows the lateral drift during a lane change.
    const double target = lane_offset(road, v.lane);
    const double x = v.lane_change_t;
    const double lateral_rate = (target - v.lane_change_from_m) * 6.0 * x * (1.0 - x) / kLaneChangeDuration;
    heading += std::atan2(lateral_rate, v.speed_mps);
  }
  v.heading_rad = heading;
}

void Traffic::step(double dt) {
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  const TrafficParams& t = scenario_.traffic;

  // Arrivals: single vehicles, convoys, or side-by-side pairs.
  for (size_t i = 0; i < lanes_.size(); ++i) {
    LaneState& lane = lanes_[i];
    while (lane.next_arrival_s <= time_) {
      const Road& road = network_.roads[lane.key.road];
      double speed = t.speed_min_mps + (t.speed_max_mps - t.speed_min_mps) * uni(rng_);
      if (!road.main) speed *= t.side_road_speed_factor;
      const double roll = uni(rng_);
      if (roll < t.convoy_probability) {
        const int members = 3 + static_cast<int>(uni(rng_) * 3.0);
        for (int m = 0; m < members; ++m) lane.pending.push_back({lane.next_arrival_s, speed, m > 0});
      } else if (roll < t.convoy_probability + t.side_by_side_probability && road.lanes_per_direction > 1) {
        lane.pending.push_back({lane.next_arrival_s, speed, false});
        const int other = lane.key.lane == 0 ? 1 : lane.key.lane - 1;
        for (LaneState& o : lanes_)
          if (o.key.road == lane.key.road && o.key.direction == lane.key.direction && o.key.lane == other)
            o.pending.push_back({lane.next_arrival_s, speed * (0.97 + 0.06 * uni(rng_)), false});
      } else {
        lane.pending.push_back({lane.next_arrival_s, speed, false});
      }
      schedule_arrivals(lane);
    }
  }
  for (LaneState& lane : lanes_) try_spawn(lane);

  // Accelerations from the state at the start of the step (simultaneous update).
  build_index();
  mark_occupied_junctions();
  std::vector<double> accel(vehicles_.size(), 0.0);
  std::vector<int> start_change(vehicles_.size(), -1);
  for (size_t i = 0; i < vehicles_.size(); ++i) {
    const Vehicle& v = vehicles_[i];
    if (v.parked || v.script >= 0) continue;
    const Road& road = network_.roads[v.road];
    double leader_speed = 0.0;
    double gap = gap_to_leader(i, v.lane, leader_speed);
    const double stop_gap = stop_line_gap(v);
    if (stop_gap < gap) {
      gap = stop_gap;
      leader_speed = 0.0;
    }
    double desired = v.desired_speed_mps;
    const double k = road.max_curvature_ahead(road_s(v), 30.0);
    if (k > 1e-4) desired = std::min(desired, std::sqrt(kLateralAccel / k));
    desired = std::max(desired, 0.1);
    const double dv = v.speed_mps - leader_speed;
    const double s_star = kMinGap + std::max(0.0, v.speed_mps * kHeadway + v.speed_mps * dv / (2.0 * std::sqrt(kMaxAccel * kComfortDecel)));
    const double free_term = std::pow(v.speed_mps / desired, 4.0);
    const double interaction = gap < 1e200 ? std::pow(s_star / std::max(gap, 0.1), 2.0) : 0.0;
    accel[i] = std::max(-9.0, kMaxAccel * (1.0 - free_term - interaction));

    // Overtaking: move to the next inner lane when held up and that lane has room.
    if (v.lane_change_t < 0.0 && road.lanes_per_direction > 1 && t.overtake_eagerness > 0.0 && v.speed_mps > 1.0) {
      const double p = t.overtake_eagerness * dt;
      if (v.lane + 1 < road.lanes_per_direction && gap < 45.0 && leader_speed < v.desired_speed_mps - 1.0) {
        double other_speed = 0.0;
        const double ahead = gap_to_leader(i, v.lane + 1, other_speed);
        const double behind = gap_to_follower(i, v.lane + 1);
        if (ahead > gap + 10.0 && behind > 8.0 + v.speed_mps && uni(rng_) < p) start_change[i] = v.lane + 1;
      } else if (v.lane > 0) {
        double other_speed = 0.0;
        const double ahead = gap_to_leader(i, v.lane - 1, other_speed);
        const double behind = gap_to_follower(i, v.lane - 1);
        if (ahead > 50.0 && behind > 15.0 + v.speed_mps && uni(rng_) < 0.3 * p) start_change[i] = v.lane - 1;
      }
    }
    // Claim the target lane at once, so a vehicle deciding later in this step sees it.
    if (start_change[i] >= 0) {
      Vehicle& changing = vehicles_[i];
      changing.lane_change_from_m = changing.lateral_m;
      changing.lane = start_change[i];
      changing.lane_change_t = 0.0;
    }
  }

  for (size_t i = 0; i < vehicles_.size(); ++i) {
    Vehicle& v = vehicles_[i];
    if (v.parked) continue;
    const cv::Point2d before = v.position_m;
    if (v.script >= 0) {
      advance_scripted(v, dt);
    } else {
      const double new_speed = std::max(0.0, v.speed_mps + accel[i] * dt);
      v.s_m += 0.5 * (v.speed_mps + new_speed) * dt;
      v.speed_mps = new_speed;
    }
    const Road& road = network_.roads[v.road];
    if (v.lane_change_t >= 0.0) {
      v.lane_change_t = std::min(1.0, v.lane_change_t + dt / kLaneChangeDuration);
      const double target = lane_offset(road, v.lane);
      v.lateral_m = v.lane_change_from_m + (target - v.lane_change_from_m) * smoothstep(v.lane_change_t);
      if (v.lane_change_t >= 1.0) v.lane_change_t = -1.0;
    }
    update_pose(v);
    v.velocity_mps = (v.position_m - before) * (1.0 / dt);
  }
  // Vehicles leave at the end of their road.
  vehicles_.erase(std::remove_if(vehicles_.begin(), vehicles_.end(),
                                 [&](const Vehicle& v) {
                                   return !v.parked && v.s_m > network_.roads[v.road].length() - v.length_m / 2.0;
                                 }),
                  vehicles_.end());
  time_ += dt;
}

}  // namespace uavmot::sim::detail
