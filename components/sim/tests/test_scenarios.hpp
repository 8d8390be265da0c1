#pragma once
// Small, fast scenarios for the simulator's tests.

#include "uavmot/sim/scenario.hpp"

namespace uavmot::sim::testing {

inline Scenario small_scenario(const std::string& preset = "paper", int frames = 6) {
  Scenario s = preset_scenario(preset);
  s.frames = frames;
  s.camera.width = 320;
  s.camera.height = 240;
  s.sensor.write_video = false;
  s.traffic.warmup_s = 40.0;
  return s;
}

// No sensor effects, so pixel values depend only on geometry.
inline Scenario clean_scenario(const std::string& preset = "paper", int frames = 6) {
  Scenario s = small_scenario(preset, frames);
  s.sensor.noise_sigma = 0.0;
  s.sensor.gain_drift = 0.0;
  s.sensor.blur_sigma_px = 0.0;
  s.sensor.jpeg_quality = 100;
  return s;
}

}  // namespace uavmot::sim::testing
