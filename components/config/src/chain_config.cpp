#include "uavmot/config/chain_config.hpp"

#include "uavmot/core/app.hpp"

namespace uavmot::config {

ChainConfig::ChainConfig(const ConfigNode& root) : root_(root) {
  root.expect_only({"scene", "motion", "segmentation", "tracking"});
  if (root.has("scene")) scene = load_scene_info(root.child("scene"));
}

ChainConfig ChainConfig::load_file(const std::string& file) { return ChainConfig(ConfigNode::load_file(file)); }

void add_node_config_options(CLI::App& app, NodeConfigArgs& args, const std::string& sections) {
  app.add_option("--config", args.file, "chain configuration YAML (uses sections " + sections + ")");
  app.add_option("--gsd", args.gsd_m, "ground sampling distance, m/px")->check(uavmot::positive_finite());
  app.add_option("--fps", args.fps, "frame rate")->check(uavmot::positive_finite());
}

ChainConfig load_node_config(const NodeConfigArgs& args) {
  ChainConfig config = args.file.empty() ? ChainConfig{} : ChainConfig::load_file(args.file);
  if (args.gsd_m > 0) config.scene.gsd_m = args.gsd_m;
  if (args.fps > 0) config.scene.fps = args.fps;
  return config;
}

}  // namespace uavmot::config
