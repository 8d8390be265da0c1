// libFuzzer: arbitrary text as a YAML configuration and as a launch profile.
// Bad input must end in uavmot::InputError (a clear message), never a crash.

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <fstream>
#include <string>

#include "uavmot/core/error.hpp"
#include "uavmot/core/scene_info.hpp"
#include "uavmot/core/yaml_config.hpp"
#include "uavmot/launch/profile.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const auto root = uavmot::ConfigNode::load_string(text, "fuzz.yaml");
    if (root.has("scene")) (void)uavmot::load_scene_info(root.child("scene"));
    int i = 0;
    double d = 0;
    std::string s;
    std::vector<std::string> list;
    bool b = false;
    for (const auto& key : root.keys()) {
      try { root.read(key, i, -100, 100); } catch (const uavmot::InputError&) {}
      try { root.read(key, d, -1e9, 1e9); } catch (const uavmot::InputError&) {}
      try { root.read(key, s); } catch (const uavmot::InputError&) {}
      try { root.read(key, list); } catch (const uavmot::InputError&) {}
      try { root.read(key, b); } catch (const uavmot::InputError&) {}
    }
  } catch (const uavmot::InputError&) {
  }
  static const std::string path = "/tmp/uavmot_config_fuzz_" + std::to_string(::getpid()) + ".yaml";
  std::ofstream(path, std::ios::trunc) << text;
  try {
    const auto profile = uavmot::launch::load_profile(path);
    (void)uavmot::launch::resolve(profile, {{"input", "x"}, {"out", "y"}});
  } catch (const uavmot::InputError&) {
  }
  return 0;
}
