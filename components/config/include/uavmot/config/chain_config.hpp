#pragma once
// The chain configuration file (bringup/chain.yaml): sections scene, motion, segmentation and
// tracking, each optional. This knows the file's shape, no layer's options: a node takes the scene
// and hands its own section to its layer's loader, so it links only its own layer.
//
//   const auto config = config::load_node_config(args);   // --config, --gsd, --fps
//   const auto options = config.layer("motion", motion::load_motion_options);
//   motion::MotionEstimator estimator(options, config.scene);

#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "uavmot/core/scene_info.hpp"
#include "uavmot/core/yaml_config.hpp"

namespace uavmot::config {

class ChainConfig {
 public:
  ChainConfig() = default;  // no file: the scene's and every layer's defaults
  // Throws InputError (file, line, key) for an unknown section or an invalid scene.
  explicit ChainConfig(const ConfigNode& root);
  static ChainConfig load_file(const std::string& file);

  SceneInfo scene;

  // A layer's options: `load` applied to its section, or the defaults when the file has none.
  // Only this layer's section is validated: each process checks the sections it uses.
  template <typename Options>
  Options layer(const std::string& section, Options (*load)(const ConfigNode&)) const {
    return root_ && root_->has(section) ? load(root_->child(section)) : Options{};
  }

 private:
  std::optional<ConfigNode> root_;
};

// The options every chain node takes: --config FILE, --gsd and --fps (which override the scene).
struct NodeConfigArgs {
  std::string file;
  double gsd_m = 0.0;  // 0: from the file
  double fps = 0.0;
};
// `sections`: what the help says the node uses, e.g. "scene and motion".
void add_node_config_options(CLI::App& app, NodeConfigArgs& args, const std::string& sections);
ChainConfig load_node_config(const NodeConfigArgs& args);

}  // namespace uavmot::config
