#pragma once
// What the chain knows about the scene: ground sampling distance, frame rate and the
// expected object size. Thresholds are configured in metres and converted here (paper III-A).

#include "uavmot/core/yaml_config.hpp"

namespace uavmot {

struct SceneInfo {
  double gsd_m = 0.35;             // metres per pixel at the image centre (paper: cars ~15 x 5 px)
  double fps = 25.0;               // frames per second
  double vehicle_length_m = 4.5;   // typical car
  double vehicle_width_m = 1.8;

  double metres_to_px(double metres) const { return metres / gsd_m; }
  double px_to_metres(double px) const { return px * gsd_m; }
  // px/frame -> m/s
  double speed_mps(double px_per_frame) const { return px_per_frame * gsd_m * fps; }
};

// Reads a `scene:` section: gsd_m, fps, vehicle_length_m, vehicle_width_m.
SceneInfo load_scene_info(const ConfigNode& node);

}  // namespace uavmot
