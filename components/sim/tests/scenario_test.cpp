#include <gtest/gtest.h>

#include "uavmot/core/error.hpp"
#include "uavmot/sim/scenario.hpp"

namespace uavmot::sim {
namespace {

TEST(Scenario, EveryPresetIsValidAndNamed) {
  for (const std::string& name : preset_names()) {
    const Scenario s = preset_scenario(name);
    EXPECT_EQ(s.name, name);
    EXPECT_NO_THROW(validate_scenario(s)) << name;
  }
  EXPECT_EQ(preset_names().size(), 9u);
}

TEST(Scenario, UnknownPresetListsTheKnownNames) {
  try {
    preset_scenario("papr");
    FAIL() << "expected InvalidArgument";
  } catch (const InvalidArgument& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("papr"), std::string::npos);
    for (const std::string& name : preset_names()) EXPECT_NE(message.find(name), std::string::npos) << name;
  }
}

TEST(Scenario, PresetsMatchTheIssue) {
  // paper: cars (4.5 m) about 13-15 px long at 0.35 m/px.
  EXPECT_NEAR(4.5 / preset_scenario("paper").camera.gsd_m, 13.0, 1.5);
  // small: cars about 8 x 3 px.
  EXPECT_NEAR(4.5 / preset_scenario("small").camera.gsd_m, 8.0, 1.0);
  EXPECT_NEAR(1.8 / preset_scenario("small").camera.gsd_m, 3.0, 0.5);
  // slow: 0.2-0.6 px/frame.
  const Scenario slow = preset_scenario("slow");
  EXPECT_NEAR(slow.traffic.speed_min_mps / slow.camera.gsd_m / slow.fps, 0.2, 1e-9);
  EXPECT_NEAR(slow.traffic.speed_max_mps / slow.camera.gsd_m / slow.fps, 0.6, 1e-9);
  // fastcam: tens of px per frame.
  const Scenario fast = preset_scenario("fastcam");
  EXPECT_GE(fast.camera.speed_mps / fast.camera.gsd_m / fast.fps, 10.0);
  // hd: 1920 x 1080.
  EXPECT_EQ(preset_scenario("hd").camera.width, 1920);
  EXPECT_EQ(preset_scenario("hd").camera.height, 1080);
}

TEST(Scenario, YamlOverridesThePresetField) {
  const Scenario s = load_scenario(ConfigNode::load_string(
      "preset: dense\nframes: 40\ncamera:\n  width: 640\n  height: 480\ntraffic:\n  parked_vehicles: 3\n", "t.yaml"));
  EXPECT_EQ(s.frames, 40);
  EXPECT_EQ(s.camera.width, 640);
  EXPECT_EQ(s.traffic.parked_vehicles, 3);
  // Untouched fields keep the dense preset's values.
  EXPECT_EQ(s.roads.main_lanes_per_direction, preset_scenario("dense").roads.main_lanes_per_direction);
  EXPECT_DOUBLE_EQ(s.traffic.convoy_probability, preset_scenario("dense").traffic.convoy_probability);
}

TEST(Scenario, YamlRoundTripKeepsEveryValue) {
  for (const std::string& name : preset_names()) {
    const Scenario s = preset_scenario(name);
    const std::string text = scenario_to_yaml(s);
    const Scenario back = load_scenario(ConfigNode::load_string(text, name + ".yaml"));
    EXPECT_EQ(scenario_to_yaml(back), text) << name;
  }
}

TEST(Scenario, ScriptedVehiclesReadAndRoundTrip) {
  const Scenario s = load_scenario(ConfigNode::load_string(
      "preset: paper\nscripted:\n"
      "  - {kind: van, gray: 90, lane: 1, direction: -1, start_m: -40.5, speed: [{at_s: 0, mps: 9}, {at_s: 3, mps: 0}],\n"
      "     lane_changes: [{at_s: 1, lane: 0}]}\n"
      "  - {start_m: 12}\n",
      "s.yaml"));
  ASSERT_EQ(s.scripted.size(), 2u);
  EXPECT_EQ(s.scripted[0].kind, "van");
  EXPECT_EQ(s.scripted[0].direction, -1);
  EXPECT_DOUBLE_EQ(s.scripted[0].start_m, -40.5);
  ASSERT_EQ(s.scripted[0].speed.size(), 2u);
  EXPECT_DOUBLE_EQ(s.scripted[0].speed[1].at_s, 3.0);
  ASSERT_EQ(s.scripted[0].lane_changes.size(), 1u);
  EXPECT_EQ(s.scripted[1].kind, "car");  // defaults
  EXPECT_DOUBLE_EQ(s.scripted[1].speed.at(0).mps, 10.0);
  const std::string text = scenario_to_yaml(s);
  EXPECT_EQ(scenario_to_yaml(load_scenario(ConfigNode::load_string(text, "back.yaml"))), text);
}

std::string load_error(const std::string& yaml) {
  try {
    load_scenario(ConfigNode::load_string(yaml, "bad.yaml"));
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(Scenario, BadScriptsNameTheVehicleAndKey) {
  EXPECT_NE(load_error("scripted:\n  - {kind: bus}\n").find("scripted[0].kind"), std::string::npos);
  EXPECT_NE(load_error("scripted:\n  - {direction: 0}\n").find("direction"), std::string::npos);
  EXPECT_NE(load_error("scripted:\n  - {speed: [{at_s: 2, mps: 1}, {at_s: 1, mps: 2}]}\n").find("increasing"), std::string::npos);
  EXPECT_NE(load_error("scripted:\n  - {speed: [{at_s: 0, mps: nan}]}\n").find("mps"), std::string::npos);
  EXPECT_NE(load_error("scripted:\n  - {sped: []}\n").find("sped"), std::string::npos);
  EXPECT_NE(load_error("scripted: 3\n").find("list"), std::string::npos);
}

TEST(Scenario, BadYamlNamesTheFileAndKey) {
  EXPECT_NE(load_error("camera:\n  widht: 640\n").find("widht"), std::string::npos);
  EXPECT_NE(load_error("camera:\n  width: 641\n").find("bad.yaml"), std::string::npos);  // odd width: video needs even
  EXPECT_NE(load_error("frames: -3\n").find("frames"), std::string::npos);
  EXPECT_NE(load_error("sensor:\n  noise_sigma: lots\n").find("noise_sigma"), std::string::npos);
  EXPECT_NE(load_error("preset: nope\n").find("preset"), std::string::npos);
  EXPECT_NE(load_error("traffic:\n  speed_min_mps: 20\n  speed_max_mps: 10\n").find("speed_min_mps"), std::string::npos);
  EXPECT_NE(load_error("camera: [1, 2]\n").find("camera"), std::string::npos);
  EXPECT_THROW(load_scenario_file("/nonexistent/scenario.yaml"), InputError);
}

TEST(Scenario, StructuresReadCheckAndRoundTrip) {
  const Scenario s = load_scenario(ConfigNode::load_string(
      "preset: paper\ncamera: {pitch_deg: 25}\nstructures:\n  building_density_per_ha: 2\n  tree_height_max_m: 12\n", "t.yaml"));
  EXPECT_DOUBLE_EQ(s.camera.pitch_deg, 25.0);
  EXPECT_DOUBLE_EQ(s.structures.building_density_per_ha, 2.0);
  EXPECT_DOUBLE_EQ(s.structures.tree_height_max_m, 12.0);
  const Scenario back = load_scenario(ConfigNode::load_string(scenario_to_yaml(s), "back.yaml"));
  EXPECT_EQ(scenario_to_yaml(back), scenario_to_yaml(s));
  EXPECT_EQ(preset_scenario("paper").structures.building_density_per_ha, 0.0);  // flat by default
  EXPECT_GT(preset_scenario("urban3d").structures.building_density_per_ha, 0.0);
  EXPECT_DOUBLE_EQ(preset_scenario("oblique").camera.pitch_deg, 30.0);
  // Bad values name the file, line and key.
  const std::string typo = load_error("structures:\n  bilding_density_per_ha: 1\n");
  EXPECT_NE(typo.find("bilding_density_per_ha"), std::string::npos);
  EXPECT_NE(typo.find("bad.yaml"), std::string::npos);
  EXPECT_NE(load_error("structures:\n  building_height_min_m: 40\n  building_height_max_m: 20\n").find("building_height_min_m"),
            std::string::npos);
  EXPECT_NE(load_error("camera:\n  pitch_deg: 60\n").find("pitch_deg"), std::string::npos);
  EXPECT_NE(load_error("camera: {altitude_m: 40}\nstructures: {building_density_per_ha: 1, building_height_max_m: 30}\n")
                .find("altitude"),
            std::string::npos);
}

}  // namespace
}  // namespace uavmot::sim
