#include "uavmot/config/chain_config.hpp"

#include <gtest/gtest.h>

namespace uavmot::config {
namespace {

struct LayerOptions {
  int value = 7;
};

LayerOptions load_layer(const ConfigNode& node) {
  LayerOptions o;
  node.expect_only({"value"});
  node.read("value", o.value, 0, 100);
  return o;
}

ChainConfig parse(const std::string& yaml) { return ChainConfig(ConfigNode::load_string(yaml, "chain.yaml")); }

TEST(ChainConfig, WithoutAFileEveryLayerGetsItsDefaults) {
  const ChainConfig config;
  EXPECT_EQ(config.scene.gsd_m, SceneInfo{}.gsd_m);
  EXPECT_EQ(config.layer("motion", load_layer).value, 7);
}

TEST(ChainConfig, ReadsTheSceneAndHandsALayerItsOwnSection) {
  const auto config = parse("scene: {gsd_m: 0.2}\nmotion: {value: 3}\n");
  EXPECT_DOUBLE_EQ(config.scene.gsd_m, 0.2);
  EXPECT_EQ(config.layer("motion", load_layer).value, 3);
  EXPECT_EQ(config.layer("tracking", load_layer).value, 7);  // absent section: defaults
}

TEST(ChainConfig, ValidatesOnlyTheSectionsAProcessUses) {
  // The motion node has no business with the tracker's keys; the tracking node rejects them.
  const auto config = parse("motion: {value: 3}\ntracking: {no_such_key: 1}\n");
  EXPECT_EQ(config.layer("motion", load_layer).value, 3);
  EXPECT_THROW(config.layer("tracking", load_layer), InputError);
}

TEST(ChainConfig, RejectsUnknownSectionsAndBadScenes) {
  EXPECT_THROW(parse("motoin: {}\n"), InputError);
  EXPECT_THROW(parse("scene: {gsd_m: -1}\n"), InputError);
}

TEST(ChainConfig, CommandLineOverridesTheScene) {
  NodeConfigArgs args;
  args.gsd_m = 0.5;
  args.fps = 10.0;
  const auto config = load_node_config(args);
  EXPECT_DOUBLE_EQ(config.scene.gsd_m, 0.5);
  EXPECT_DOUBLE_EQ(config.scene.fps, 10.0);
  EXPECT_DOUBLE_EQ(config.scene.vehicle_length_m, SceneInfo{}.vehicle_length_m);
}

TEST(ChainConfig, NodeOptionsParse) {
  CLI::App app;
  NodeConfigArgs args;
  add_node_config_options(app, args, "scene and motion");
  const char* argv[] = {"node", "--gsd", "0.25", "--fps", "12"};
  app.parse(5, argv);
  EXPECT_DOUBLE_EQ(args.gsd_m, 0.25);
  EXPECT_DOUBLE_EQ(args.fps, 12.0);
  EXPECT_TRUE(args.file.empty());
}

}  // namespace
}  // namespace uavmot::config
