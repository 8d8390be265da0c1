#pragma once
// Every parameter of a simulated UAV sequence. Lengths in metres, speeds in m/s, angles in
// degrees, times in seconds. A scenario YAML mirrors this struct section by section
// (docs/sim.md); presets are named, ready-made scenarios.

#include <cstdint>
#include <string>
#include <vector>

#include "uavmot/core/yaml_config.hpp"

namespace uavmot::sim {

// The virtual camera (nadir unless pitched) and its smooth trajectory.
struct CameraParams {
  int width = 1024;               // px
  int height = 768;               // px
  double gsd_m = 0.35;            // metres per pixel at the image centre at the nominal altitude
  double altitude_m = 300.0;      // nominal height above ground (sets the focal length f = altitude / gsd)
  double speed_mps = 2.0;         // ground speed of the camera
  double heading_deg = 30.0;      // direction of travel on the ground, from the world x-axis
  double path_curvature_dps = 0.0;  // how fast the direction of travel turns
  double yaw_deg = 0.0;           // initial rotation of the image about the optical axis
  double yaw_rate_dps = 0.2;      // steady yaw rate
  double yaw_wobble_deg = 0.3;    // amplitude of a slow sinusoidal yaw wobble
  double altitude_change = 0.0;   // relative amplitude of the altitude (zoom) oscillation, 0.1 = +-10 %
  double altitude_period_s = 12.0;
  double tilt_deg = 1.0;          // amplitude of the pitch and roll wobble (perspective)
  double wobble_period_s = 9.0;   // period of the yaw/tilt wobble
  double pitch_deg = 0.0;         // mean forward pitch (oblique view); 0 = nadir. The tilt wobble adds to it
};

// The ground: real aerial texture with roads drawn on it.
struct GroundParams {
  std::string texture_dir;        // folder of images; "" = the CLIF 2007 frames in data/; "procedural" = synthetic
  double texture_gsd_m = 1.0;     // metres per texture pixel
  double texture_contrast = 1.0;  // scales the texture's deviation from its mean
  double detail_noise = 5.0;      // gray-level spread of fine ground grain added at rendering resolution
  int raster_max_megapixels = 120;  // refuse scenarios that need a larger ground raster
};

// The road network, generated around the camera path.
struct RoadParams {
  double main_road_angle_deg = 20.0;  // main road direction relative to the camera's direction of travel
  int main_lanes_per_direction = 2;
  int cross_roads = 1;            // straight roads crossing the main road
  int curved_roads = 1;           // roads with a 90-degree bend (turning traffic)
  int side_lanes_per_direction = 1;
  double lane_width_m = 3.5;
  double asphalt_gray = 85.0;     // 0..255
  double asphalt_opacity = 0.9;   // how much of the underlying texture is replaced
  double marking_gray = 215.0;
  double marking_width_m = 0.15;
  double dash_length_m = 3.0;
  double dash_gap_m = 6.0;
};

// Vehicles: kinds, colours, speeds and the traffic situations they produce.
struct TrafficParams {
  double flow_per_lane_vph = 600.0;   // vehicles per hour entering each lane
  double speed_min_mps = 8.0;         // desired speeds are drawn uniformly in [min, max]
  double speed_max_mps = 14.0;
  double side_road_speed_factor = 0.7;
  double van_fraction = 0.15;
  double truck_fraction = 0.08;
  double dark_fraction = 0.3;         // share of dark cars with little contrast to asphalt
  double convoy_probability = 0.2;    // chance that a spawn is a convoy of 3-5 vehicles
  double overtake_eagerness = 1.0;    // 0 = never change lanes
  double side_by_side_probability = 0.1;  // chance that a spawn is a pair in adjacent lanes at similar speed
  double stop_period_s = 30.0;        // stop-and-go: a stop line on the main road cycles red/green
  double stop_red_s = 10.0;           // 0 = no stop line
  int parked_vehicles = 12;           // parked along the roads and in a lot; they never move
  double moving_threshold_mps = 0.5;  // a vehicle slower than this is not a moving object
  double warmup_s = 60.0;             // simulated before frame 1 so traffic is in steady state
  double shadow_length_m = 0.8;       // sun shadow offset
  double shadow_angle_deg = 35.0;     // direction of the shadow on the ground
  double shadow_strength = 0.45;      // 0 = no shadow, 1 = black
  double vehicle_size_scale = 1.0;    // scales every generated vehicle's length and width
};

// Static 3-D structure standing on the ground: buildings, trees and walls. They are placed
// from the seed off the asphalt, and drawn with the true pinhole camera, so their upper parts
// show parallax against the ground plane. Densities are per hectare of the ground the
// sequence sees; all zero (the default) = a flat world.
struct StructureParams {
  double building_density_per_ha = 0.0;
  double building_size_min_m = 10.0;   // footprint sides, uniform in [min, max]
  double building_size_max_m = 30.0;
  double building_height_min_m = 5.0;
  double building_height_max_m = 30.0;
  double building_roadside_fraction = 0.5;  // share placed right beside a road or parking lot
  double tree_density_per_ha = 0.0;
  double tree_radius_min_m = 2.0;      // canopy radius
  double tree_radius_max_m = 6.0;
  double tree_height_min_m = 5.0;      // top of the canopy
  double tree_height_max_m = 20.0;
  double tree_roadside_fraction = 0.5;  // share standing at a road edge with the canopy over the asphalt
  double wall_density_per_ha = 0.0;
  double wall_length_min_m = 10.0;
  double wall_length_max_m = 40.0;
  double wall_height_min_m = 1.5;
  double wall_height_max_m = 4.0;
  double sun_azimuth_deg = 215.0;      // direction the light comes from (world x-axis = 0), shades the walls
  double sun_elevation_deg = 45.0;
};

// What the sensor does to the image.
struct SensorParams {
  double blur_sigma_px = 0.6;
  double noise_sigma = 2.0;           // gray levels, additive Gaussian
  double gain_drift = 0.04;           // relative amplitude of a slow gain oscillation
  double gain_period_s = 7.0;
  double brightness_offset = 0.0;     // gray levels added
  double contrast = 1.0;              // scales the whole image about mid-gray
  int jpeg_quality = 92;
  bool write_video = true;            // video.mp4 beside the JPEG frames
};

// A vehicle that drives to a script instead of the traffic model, for scenario tests
// (overtaking, convoys, re-entering the view, stop-and-go). Times are from frame 1; it ignores
// other vehicles and signals (the traffic model's vehicles do react to it).
struct SpeedKey {
  double at_s = 0.0;
  double mps = 0.0;
};
struct LaneChange {
  double at_s = 0.0;  // the change starts here and takes 3.5 s, like the traffic model's
  int lane = 0;
};
struct ScriptedVehicle {
  std::string kind = "car";      // car | van | truck
  double length_m = 4.6;
  double width_m = 1.8;
  double gray = 200.0;           // body luminance 0..255 (roof and glass follow from it)
  int road = 0;                  // 0 = the main road
  int direction = 1;             // +1 along the road, -1 against it
  int lane = 0;                  // 0 = outermost
  // Start along the lane, from the point nearest the image centre at frame 1; negative = behind it.
  double start_m = 0.0;
  std::vector<SpeedKey> speed{{0.0, 10.0}};  // linear between keys, held before the first and after the last
  std::vector<LaneChange> lane_changes;
};

struct Scenario {
  std::string name = "paper";
  int frames = 250;
  double fps = 25.0;
  CameraParams camera;
  GroundParams ground;
  RoadParams roads;
  TrafficParams traffic;
  StructureParams structures;
  SensorParams sensor;
  std::vector<ScriptedVehicle> scripted;  // YAML: a `scripted:` list (docs/sim.md)
};

// Names of the built-in presets, in a fixed order.
const std::vector<std::string>& preset_names();
// Throws uavmot::InvalidArgument listing the names when `name` is unknown.
Scenario preset_scenario(const std::string& name);
// The same kind of scene with its look and layout drawn from `seed` around `base` (`uavmot sim
// --vary`), so that test data varies as much as real flights do: road layout and asphalt, vehicle
// mix, colours and sizes, sun and shadows, the camera's heading, speed, GSD, frame rate and
// resolution, blur, noise, gain and JPEG quality. Ranges are relative to `base`, so a preset keeps
// its character (`small` stays small, `slow` slow). Deterministic in `seed`.
Scenario vary_scenario(const Scenario& base, uint64_t seed);
// Reads a scenario YAML (optionally `preset: NAME` as the base, then sections that override it).
// Throws InputError naming file, line and key on anything invalid.
Scenario load_scenario(const ConfigNode& node);
Scenario load_scenario_file(const std::string& file);
// Checks cross-field consistency (min <= max etc.); throws InputError.
void validate_scenario(const Scenario& scenario);
// The whole scenario as YAML text that load_scenario reads back to the same values.
std::string scenario_to_yaml(const Scenario& scenario);

// Where the CLIF 2007 frames of data/ are (compile-time default, overridable by UAVMOT_DATA_DIR).
std::string default_texture_dir();

}  // namespace uavmot::sim
