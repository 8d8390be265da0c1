#include "uavmot/sim/scenario.hpp"

#include <algorithm>
#include <cstdlib>
#include <optional>
#include <sstream>

#include <fmt/format.h>

#include "scenario_fields.hpp"
#include "uavmot/build_paths/build_paths.hpp"
#include "uavmot/core/error.hpp"

namespace uavmot::sim {
namespace {

// Reads the fields present in a ConfigNode, leaving the others at the base scenario's values.
class YamlReader : public detail::FieldVisitor {
 public:
  explicit YamlReader(const ConfigNode& root) { stack_.push_back(Level{root, {}}); }

  void begin_section(const char* name) override {
    Level& parent = stack_.back();
    parent.known.push_back(name);
    std::optional<ConfigNode> node;
    if (parent.node && parent.node->has(name)) node = parent.node->child(name);
    stack_.push_back(Level{node, {}});
  }
  void end_section() override {
    check_keys(stack_.back());
    stack_.pop_back();
  }
  void field(const char* key, int& value, int min, int max) override {
    if (note(key)) stack_.back().node->read(key, value, min, max);
  }
  void field(const char* key, double& value, double min, double max) override {
    if (note(key)) stack_.back().node->read(key, value, min, max);
  }
  void field(const char* key, bool& value) override {
    if (note(key)) stack_.back().node->read(key, value);
  }
  void field(const char* key, std::string& value) override {
    if (note(key)) stack_.back().node->read(key, value);
  }
  void finish(const std::vector<std::string>& extra_top_level_keys) {
    for (const auto& k : extra_top_level_keys) stack_.front().known.push_back(k);
    check_keys(stack_.front());
  }

 private:
  struct Level {
    std::optional<ConfigNode> node;
    std::vector<std::string> known;
  };
  bool note(const char* key) {
    Level& level = stack_.back();
    level.known.push_back(key);
    return level.node && level.node->has(key);
  }
  static void check_keys(const Level& level) {
    if (level.node) level.node->expect_only(level.known);
  }
  std::vector<Level> stack_;
};

// Writes every field as YAML, sections as nested maps.
class YamlWriter : public detail::FieldVisitor {
 public:
  void begin_section(const char* name) override {
    out_ << name << ":\n";
    indent_ = "  ";
  }
  void end_section() override { indent_.clear(); }
  void field(const char* key, int& value, int, int) override { out_ << indent_ << key << ": " << value << "\n"; }
  void field(const char* key, double& value, double, double) override {
    // Shortest text that reads back to the same double.
    out_ << indent_ << key << ": " << fmt::format("{}", value) << "\n";
  }
  void field(const char* key, bool& value) override { out_ << indent_ << key << ": " << (value ? "true" : "false") << "\n"; }
  void field(const char* key, std::string& value) override { out_ << indent_ << key << ": \"" << value << "\"\n"; }
  std::string text() const { return out_.str(); }

 private:
  std::ostringstream out_;
  std::string indent_;
};

ScriptedVehicle load_scripted_vehicle(const ConfigNode& node) {
  ScriptedVehicle v;
  node.expect_only({"kind", "length_m", "width_m", "gray", "road", "direction", "lane", "start_m", "speed", "lane_changes"});
  node.read_choice("kind", v.kind, {"car", "van", "truck"});
  node.read("length_m", v.length_m, 1.0, 30.0);
  node.read("width_m", v.width_m, 0.5, 4.0);
  node.read("gray", v.gray, 0.0, 255.0);
  node.read("road", v.road, 0, 20);
  node.read("direction", v.direction, -1, 1);
  if (v.direction == 0) node.fail("direction", "must be 1 (along the road) or -1 (against it)");
  node.read("lane", v.lane, 0, 3);
  node.read("start_m", v.start_m, -10000.0, 10000.0);
  if (node.has("speed")) {
    v.speed.clear();
    for (const ConfigNode& key : node.children("speed")) {
      key.expect_only({"at_s", "mps"});
      SpeedKey k;
      key.read("at_s", k.at_s, 0.0, 1e6);
      key.read("mps", k.mps, 0.0, 100.0);
      if (!v.speed.empty() && k.at_s <= v.speed.back().at_s) key.fail("at_s", "speed keys must be in increasing time");
      v.speed.push_back(k);
    }
    if (v.speed.empty()) node.fail("speed", "needs at least one {at_s, mps} key");
  }
  if (node.has("lane_changes")) {
    for (const ConfigNode& change : node.children("lane_changes")) {
      change.expect_only({"at_s", "lane"});
      LaneChange c;
      change.read("at_s", c.at_s, 0.0, 1e6);
      change.read("lane", c.lane, 0, 3);
      if (!v.lane_changes.empty() && c.at_s < v.lane_changes.back().at_s + 3.5)
        change.fail("at_s", "a lane change starts at least 3.5 s after the previous one (they take 3.5 s)");
      v.lane_changes.push_back(c);
    }
  }
  return v;
}

std::string scripted_to_yaml(const std::vector<ScriptedVehicle>& vehicles) {
  if (vehicles.empty()) return {};
  std::string out = "scripted:\n";
  for (const ScriptedVehicle& v : vehicles) {
    out += fmt::format("  - kind: \"{}\"\n    length_m: {}\n    width_m: {}\n    gray: {}\n", v.kind, v.length_m, v.width_m, v.gray);
    out += fmt::format("    road: {}\n    direction: {}\n    lane: {}\n    start_m: {}\n    speed:\n", v.road, v.direction, v.lane, v.start_m);
    for (const SpeedKey& k : v.speed) out += fmt::format("      - {{at_s: {}, mps: {}}}\n", k.at_s, k.mps);
    if (!v.lane_changes.empty()) out += "    lane_changes:\n";
    for (const LaneChange& c : v.lane_changes) out += fmt::format("      - {{at_s: {}, lane: {}}}\n", c.at_s, c.lane);
  }
  return out;
}

std::string join_names() {
  std::string names;
  for (const auto& n : preset_names()) names += (names.empty() ? "" : ", ") + n;
  return names;
}

}  // namespace

const std::vector<std::string>& preset_names() {
  static const std::vector<std::string> names{"paper", "lowsnr", "fastcam", "dense", "slow", "small", "hd", "urban3d", "oblique"};
  return names;
}

Scenario preset_scenario(const std::string& name) {
  Scenario s;  // the defaults are the `paper` preset
  s.name = name;
  if (name == "paper") {
    // About 0.35 m/px so cars are about 13-15 x 5 px; slow camera drift (paper Section V).
    return s;
  }
  if (name == "lowsnr") {
    // Dim, noisy, low-contrast imagery: many dark cars on dark asphalt.
    s.sensor.noise_sigma = 6.0;
    s.sensor.blur_sigma_px = 1.0;
    s.sensor.contrast = 0.6;
    s.sensor.brightness_offset = -20.0;
    s.sensor.gain_drift = 0.08;
    s.sensor.jpeg_quality = 70;
    s.traffic.dark_fraction = 0.55;
    return s;
  }
  if (name == "fastcam") {
    // Tens of px per frame with yaw and zoom: a fast, manoeuvring platform.
    s.camera.width = 800;
    s.camera.height = 600;
    s.camera.speed_mps = 180.0;  // ~20 px/frame at 0.35 m/px and 25 fps
    s.camera.heading_deg = 10.0;
    s.camera.path_curvature_dps = 2.0;
    s.camera.yaw_rate_dps = 4.0;
    s.camera.yaw_wobble_deg = 2.0;
    s.camera.altitude_change = 0.15;
    s.camera.altitude_period_s = 6.0;
    s.camera.tilt_deg = 3.0;
    s.camera.wobble_period_s = 4.0;
    s.roads.main_road_angle_deg = 0.0;
    s.roads.cross_roads = 3;
    s.roads.curved_roads = 1;
    s.traffic.flow_per_lane_vph = 1200.0;
    s.traffic.parked_vehicles = 30;
    return s;
  }
  if (name == "dense") {
    // Heavy traffic: overtaking pairs, convoys, queues at the stop line.
    s.roads.main_lanes_per_direction = 3;
    s.roads.cross_roads = 2;
    s.traffic.flow_per_lane_vph = 1500.0;
    s.traffic.convoy_probability = 0.45;
    s.traffic.side_by_side_probability = 0.35;
    s.traffic.overtake_eagerness = 2.0;
    s.traffic.parked_vehicles = 30;
    s.traffic.stop_period_s = 24.0;
    s.traffic.stop_red_s = 9.0;
    return s;
  }
  if (name == "slow") {
    // Sub-pixel movers: 0.2-0.6 px/frame at 0.35 m/px and 25 fps.
    s.camera.speed_mps = 1.0;
    s.traffic.speed_min_mps = 0.2 * 0.35 * 25.0;
    s.traffic.speed_max_mps = 0.6 * 0.35 * 25.0;
    s.traffic.side_road_speed_factor = 1.0;
    s.traffic.flow_per_lane_vph = 700.0;
    s.traffic.moving_threshold_mps = 0.3;
    return s;
  }
  if (name == "small") {
    // Higher altitude: cars about 8 x 3 px.
    s.camera.gsd_m = 0.6;
    s.camera.altitude_m = 500.0;
    s.camera.speed_mps = 6.0;
    s.roads.cross_roads = 2;
    s.roads.curved_roads = 2;
    s.traffic.parked_vehicles = 25;
    return s;
  }
  if (name == "hd") {
    // 1920 x 1080 for throughput measurements.
    s.camera.width = 1920;
    s.camera.height = 1080;
    s.camera.gsd_m = 0.3;
    s.camera.speed_mps = 4.0;
    s.roads.cross_roads = 2;
    s.roads.curved_roads = 1;
    s.traffic.parked_vehicles = 30;
    return s;
  }
  if (name == "urban3d" || name == "oblique") {
    // A town: buildings 5-30 m, trees over the road edges, walls, parked vehicles among them.
    s.roads.cross_roads = 2;
    s.traffic.parked_vehicles = 20;
    s.structures.building_density_per_ha = 1.6;
    s.structures.tree_density_per_ha = 2.5;
    s.structures.wall_density_per_ha = 0.5;
    s.camera.speed_mps = 36.0;
    if (name == "urban3d") {
      // Nadir at 300 m like `paper`, but a fixed-wing platform at 36 m/s (4.1 px/frame): the
      // parallax of a roof against the ground is v dt h / (gsd (H - h)) = 0.29 px/frame at 20 m
      // and 0.46 px/frame at 30 m.
      return s;
    }
    // Oblique: pitched 30 deg forward, the GSD grows from the near to the far edge of the image.
    s.camera.pitch_deg = 30.0;
    s.camera.heading_deg = 120.0;  // across the view direction
    return s;
  }
  throw InvalidArgument("unknown scenario preset '" + name + "'; known presets: " + join_names());
}

Scenario load_scenario(const ConfigNode& node) {
  Scenario s;
  if (node.has("preset")) {
    std::string preset;
    node.read_choice("preset", preset, preset_names());
    s = preset_scenario(preset);
  }
  YamlReader reader(node);
  detail::visit_scenario(s, reader);
  reader.finish({"preset", "scripted"});
  if (node.has("scripted")) {
    s.scripted.clear();
    for (const ConfigNode& vehicle : node.children("scripted")) s.scripted.push_back(load_scripted_vehicle(vehicle));
  }
  try {
    validate_scenario(s);
  } catch (const InputError& e) {
    throw InputError(node.location() + ": " + e.what());
  }
  return s;
}

Scenario load_scenario_file(const std::string& file) { return load_scenario(ConfigNode::load_file(file)); }

void validate_scenario(const Scenario& s) {
  if (s.traffic.speed_min_mps > s.traffic.speed_max_mps)
    throw InputError("traffic.speed_min_mps (" + std::to_string(s.traffic.speed_min_mps) +
                     ") is larger than traffic.speed_max_mps (" + std::to_string(s.traffic.speed_max_mps) + ")");
  if (s.traffic.van_fraction + s.traffic.truck_fraction > 1.0)
    throw InputError("traffic.van_fraction + traffic.truck_fraction exceed 1");
  if (s.traffic.stop_red_s >= s.traffic.stop_period_s && s.traffic.stop_red_s > 0.0)
    throw InputError("traffic.stop_red_s must be shorter than traffic.stop_period_s");
  if (s.frames < 1) throw InputError("frames must be at least 1");
  const StructureParams& b = s.structures;
  const std::pair<const char*, std::pair<double, double>> ranges[] = {
      {"building_size", {b.building_size_min_m, b.building_size_max_m}},
      {"building_height", {b.building_height_min_m, b.building_height_max_m}},
      {"tree_radius", {b.tree_radius_min_m, b.tree_radius_max_m}},
      {"tree_height", {b.tree_height_min_m, b.tree_height_max_m}},
      {"wall_length", {b.wall_length_min_m, b.wall_length_max_m}},
      {"wall_height", {b.wall_height_min_m, b.wall_height_max_m}}};
  for (const auto& [key, range] : ranges)
    if (range.first > range.second)
      throw InputError(std::string("structures.") + key + "_min_m (" + std::to_string(range.first) + ") is larger than structures." +
                       key + "_max_m (" + std::to_string(range.second) + ")");
  const double lowest_camera = s.camera.altitude_m * (1.0 - s.camera.altitude_change);
  const double tallest = std::max({b.building_density_per_ha > 0.0 ? b.building_height_max_m : 0.0,
                                   b.tree_density_per_ha > 0.0 ? b.tree_height_max_m : 0.0,
                                   b.wall_density_per_ha > 0.0 ? b.wall_height_max_m : 0.0});
  if (tallest > 0.5 * lowest_camera)
    throw InputError("structures taller than half the camera's lowest altitude (" + std::to_string(lowest_camera) +
                     " m): lower structures.*_height_max_m or raise camera.altitude_m");
  if (s.camera.width % 2 != 0 || s.camera.height % 2 != 0)
    throw InputError("camera.width and camera.height must be even (video encoding)");
}

std::string scenario_to_yaml(const Scenario& scenario) {
  Scenario copy = scenario;
  YamlWriter writer;
  detail::visit_scenario(copy, writer);
  return writer.text() + scripted_to_yaml(scenario.scripted);
}

std::string default_texture_dir() {
  if (const char* data = std::getenv("UAVMOT_DATA_DIR"); data && *data)
    return std::string(data) + "/clif2007/jpg";
  return build_paths::data_dir() + "/clif2007/jpg";
}

}  // namespace uavmot::sim
