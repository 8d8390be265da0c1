#include "uavmot/core/scene_info.hpp"

namespace uavmot {

SceneInfo load_scene_info(const ConfigNode& node) {
  SceneInfo scene;
  node.expect_only({"gsd_m", "fps", "vehicle_length_m", "vehicle_width_m"});
  node.read("gsd_m", scene.gsd_m, 1e-3, 100.0);
  node.read("fps", scene.fps, 0.01, 1000.0);
  node.read("vehicle_length_m", scene.vehicle_length_m, 0.1, 100.0);
  node.read("vehicle_width_m", scene.vehicle_width_m, 0.1, 100.0);
  return scene;
}

}  // namespace uavmot
