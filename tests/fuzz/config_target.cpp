// Fuzz target: arbitrary text as a chain configuration (bringup/chain.yaml: scene, motion,
// segmentation, tracking) and as a bringup profile (bringup/local.yaml). Bad input must end in
// uavmot::InputError naming the file and key, never a crash or another exception; a
// configuration the loader accepts must also be accepted by the chain it configures.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "fuzz_targets.hpp"
#include "scratch_dir.hpp"
#include "uavmot/core/error.hpp"
#include "uavmot/core/scene_info.hpp"
#include "uavmot/core/yaml_config.hpp"
#include "uavmot/launch/profile.hpp"
#include "uavmot/pipeline/chain.hpp"

namespace uavmot::fuzz {
namespace {

// The typed readers on every top-level key: each either reads or throws InputError.
void read_every_key(const ConfigNode& root) {
  int i = 0;
  double d = 0;
  std::string s;
  std::vector<std::string> list;
  bool b = false;
  for (const auto& key : root.keys()) {
    try { root.read(key, i, -100, 100); } catch (const InputError&) {}
    try { root.read(key, d, -1e9, 1e9); } catch (const InputError&) {}
    try { root.read(key, s); } catch (const InputError&) {}
    try { root.read(key, list); } catch (const InputError&) {}
    try { root.read(key, b); } catch (const InputError&) {}
  }
}

}  // namespace

int config(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const auto root = ConfigNode::load_string(text, "fuzz.yaml");
    read_every_key(root);
    const auto options = pipeline::load_chain_options(root);
    pipeline::Chain chain(options);
  } catch (const InputError&) {
  }
  static const std::string path = test_support::scratch_path("config_fuzz_profile.yaml").string();
  std::ofstream(path, std::ios::trunc) << text;
  try {
    const auto profile = launch::load_profile(path);
    (void)launch::resolve(profile, {{"input", "x"}, {"out", "y"}, {"gsd", "0.3"}, {"fps", "25"},
                                     {"profile_dir", "/p"}, {"run_dir", "/r"}});
  } catch (const InputError&) {
  }
  return 0;
}

}  // namespace uavmot::fuzz
