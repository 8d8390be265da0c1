// vary_scenario: a preset's scene redrawn from a seed (scenario.hpp). Every draw comes from one
// generator seeded here, in a fixed order, so a seed always gives the same scene.

#include <algorithm>
#include <cmath>
#include <random>

#include "uavmot/sim/scenario.hpp"

namespace uavmot::sim {
namespace {

constexpr double kPi = 3.14159265358979323846;

// SplitMix64's finaliser: mt19937_64's first outputs for nearby seeds are alike (seeds 100-103
// all drew the same frame size), so the seed is scrambled before it seeds the generator.
uint64_t scramble(uint64_t x) {
  x += 0x9E3779B97F4A7C15ULL;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
  return x ^ (x >> 31);
}

class Draw {
 public:
  explicit Draw(uint64_t seed) : rng_(scramble(seed ^ 0x5CE4E7A41ULL)) {}
  double uniform(double lo, double hi) { return lo + (hi - lo) * std::uniform_real_distribution<double>(0.0, 1.0)(rng_); }
  double scaled(double value, double lo, double hi) { return value * uniform(lo, hi); }  // value x U(lo, hi)
  int integer(int lo, int hi) { return lo + static_cast<int>(std::min(uniform(0.0, 1.0), 0.999999) * (hi - lo + 1)); }
  bool chance(double p) { return uniform(0.0, 1.0) < p; }
  template <class T, size_t N>
  const T& pick(const T (&choices)[N]) { return choices[static_cast<size_t>(integer(0, static_cast<int>(N) - 1))]; }

 private:
  std::mt19937_64 rng_;
};

struct Resolution {
  int width, height;
};

void vary_camera(CameraParams& c, Draw& d) {
  // Frame sizes of common UAV sensors, in the preset's class (an HD preset stays HD).
  static const Resolution kStandard[] = {{800, 600}, {960, 540}, {1024, 768}, {1280, 720}, {1280, 960}};
  static const Resolution kHigh[] = {{1600, 1200}, {1920, 1080}, {1920, 1200}};
  const Resolution r = c.width > 1280 ? d.pick(kHigh) : d.pick(kStandard);
  c.width = r.width;
  c.height = r.height;
  c.gsd_m = d.scaled(c.gsd_m, 0.85, 1.15);
  c.speed_mps = d.scaled(c.speed_mps, 0.6, 1.5);
  c.heading_deg = d.uniform(0.0, 360.0);
  c.yaw_deg = d.uniform(0.0, 360.0);
  c.yaw_rate_dps = d.scaled(c.yaw_rate_dps, 0.5, 1.5) * (d.chance(0.5) ? -1.0 : 1.0);
  c.tilt_deg = d.scaled(c.tilt_deg, 0.5, 1.5);
}

void vary_roads(RoadParams& r, Draw& d) {
  r.main_road_angle_deg = d.uniform(0.0, 90.0);
  r.main_lanes_per_direction = std::clamp(r.main_lanes_per_direction + d.integer(-1, 1), 1, 4);
  r.cross_roads = std::clamp(r.cross_roads + d.integer(-1, 1), 0, 4);
  r.curved_roads = std::clamp(r.curved_roads + d.integer(-1, 1), 0, 3);
  r.asphalt_gray = d.uniform(60.0, 120.0);
  r.asphalt_opacity = d.uniform(0.75, 0.95);
  r.marking_gray = d.uniform(170.0, 230.0);
}

// Traffic and the sun; `sun` is the structures' light, kept opposite the vehicles' shadows.
void vary_traffic_and_sun(TrafficParams& t, StructureParams& sun, Draw& d) {
  const double speed_scale = d.uniform(0.75, 1.2);  // both ends, so a slow preset stays slow
  t.speed_min_mps *= speed_scale;
  t.speed_max_mps *= speed_scale;
  t.flow_per_lane_vph = d.scaled(t.flow_per_lane_vph, 0.7, 1.3);
  t.van_fraction = std::clamp(d.scaled(t.van_fraction, 0.5, 1.5), 0.0, 0.4);
  t.truck_fraction = std::clamp(d.scaled(t.truck_fraction, 0.5, 1.5), 0.0, 0.2);
  t.dark_fraction = std::clamp(t.dark_fraction + d.uniform(-0.15, 0.15), 0.05, 0.8);
  t.vehicle_size_scale = d.uniform(0.9, 1.1);
  t.parked_vehicles = static_cast<int>(std::lround(d.scaled(t.parked_vehicles, 0.5, 1.5)));
  // The sun: anywhere around, 30-70 deg high; shadows lengthen as it sinks.
  const double elevation = d.uniform(30.0, 70.0);
  t.shadow_angle_deg = d.uniform(0.0, 360.0);
  t.shadow_length_m *= std::tan(45.0 * kPi / 180.0) / std::tan(elevation * kPi / 180.0);
  t.shadow_strength = d.uniform(0.25, 0.6);
  sun.sun_azimuth_deg = std::fmod(t.shadow_angle_deg + 180.0, 360.0);
  sun.sun_elevation_deg = elevation;
}

void vary_sensor(SensorParams& s, GroundParams& g, Draw& d) {
  s.blur_sigma_px = d.scaled(s.blur_sigma_px, 0.7, 1.6);
  s.noise_sigma = d.scaled(s.noise_sigma, 0.7, 1.5);
  s.gain_drift = d.scaled(s.gain_drift, 0.5, 1.5);
  s.contrast = std::clamp(d.scaled(s.contrast, 0.85, 1.1), 0.1, 2.0);
  s.brightness_offset += d.uniform(-15.0, 15.0);
  s.jpeg_quality = std::clamp(s.jpeg_quality + d.integer(-20, 3), 60, 95);
  g.texture_contrast = d.scaled(g.texture_contrast, 0.8, 1.2);
}

}  // namespace

Scenario vary_scenario(const Scenario& base, uint64_t seed) {
  Scenario s = base;
  Draw d(seed);
  vary_camera(s.camera, d);
  vary_roads(s.roads, d);
  vary_traffic_and_sun(s.traffic, s.structures, d);
  vary_sensor(s.sensor, s.ground, d);
  s.fps = d.chance(0.3) ? 30.0 : base.fps;
  return s;
}

}  // namespace uavmot::sim
