// The traffic model produces the situations the paper's chain must handle.
#include <cmath>
#include <map>
#include <set>

#include <gtest/gtest.h>

#include "../src/road_network.hpp"
#include "../src/traffic.hpp"
#include "uavmot/sim/scenario.hpp"

namespace uavmot::sim::detail {
namespace {

struct World {
  Scenario scenario = preset_scenario("dense");
  RoadNetwork network;
  std::unique_ptr<Traffic> traffic;
  explicit World(uint64_t seed) {
    network = make_road_network(scenario, {0, 0}, 400.0, 250.0, seed);
    traffic = std::make_unique<Traffic>(scenario, network, cv::Point2d(0, 0), 250.0, seed);
  }
};

TEST(Traffic, StopAndGoOvertakingTurnsAndParkedVehicles) {
  World w(3);
  const double dt = 1.0 / 25.0;
  std::map<int, double> min_speed, max_speed_after_stop;
  std::map<int, cv::Point2d> parked_at;
  std::map<int, std::pair<double, double>> heading_range;  // curved-road vehicles
  std::set<int> changed_lane;
  for (const Vehicle& v : w.traffic->vehicles())
    if (v.parked) parked_at[v.internal_id] = v.position_m;
  ASSERT_FALSE(parked_at.empty());
  for (int step = 0; step < 25 * 90; ++step) {
    w.traffic->step(dt);
    for (const Vehicle& v : w.traffic->vehicles()) {
      if (v.parked) {
        EXPECT_EQ(v.position_m, parked_at.at(v.internal_id));
        EXPECT_EQ(v.speed_mps, 0.0);
        continue;
      }
      if (v.lane_change_t >= 0.0) changed_lane.insert(v.internal_id);
      if (!min_speed.count(v.internal_id)) min_speed[v.internal_id] = v.speed_mps;
      min_speed[v.internal_id] = std::min(min_speed[v.internal_id], v.speed_mps);
      if (min_speed[v.internal_id] < 0.1) max_speed_after_stop[v.internal_id] = std::max(max_speed_after_stop[v.internal_id], v.speed_mps);
      const double curvature_max = w.network.roads[v.road].curvature.empty() ? 0.0 : *std::max_element(
          w.network.roads[v.road].curvature.begin(), w.network.roads[v.road].curvature.end());
      if (curvature_max > 0.01) {
        auto [it, fresh] = heading_range.emplace(v.internal_id, std::make_pair(v.heading_rad, v.heading_rad));
        // Unwrap against the first heading seen.
        double h = v.heading_rad;
        while (h - it->second.first > M_PI) h -= 2 * M_PI;
        while (h - it->second.first < -M_PI) h += 2 * M_PI;
        it->second.first = std::min(it->second.first, h);
        it->second.second = std::max(it->second.second, h);
      }
    }
  }
  int stopped_then_went = 0;
  for (const auto& [id, speed] : max_speed_after_stop)
    if (speed > 3.0) ++stopped_then_went;
  EXPECT_GT(stopped_then_went, 3) << "stop-and-go at the signals";
  EXPECT_GT(changed_lane.size(), 3u) << "overtaking manoeuvres";
  int turned = 0;
  for (const auto& [id, range] : heading_range)
    if (range.second - range.first > 1.3) ++turned;  // about 90 degrees
  EXPECT_GT(turned, 0) << "vehicles driving through a bend";
}

TEST(Traffic, SameSeedSameTraffic) {
  World a(8), b(8);
  for (int step = 0; step < 250; ++step) {
    a.traffic->step(0.04);
    b.traffic->step(0.04);
  }
  ASSERT_EQ(a.traffic->vehicles().size(), b.traffic->vehicles().size());
  for (size_t i = 0; i < a.traffic->vehicles().size(); ++i) {
    EXPECT_EQ(a.traffic->vehicles()[i].internal_id, b.traffic->vehicles()[i].internal_id);
    EXPECT_EQ(a.traffic->vehicles()[i].position_m, b.traffic->vehicles()[i].position_m);
  }
}

}  // namespace
}  // namespace uavmot::sim::detail
