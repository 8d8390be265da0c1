// Fuzz target: arbitrary bytes as a damaged recording, as a user meets one after a crash or a cut
// transfer: `uavmot record --recover` (mcap::recover) repairs it, then `uavmot eval --recording`
// reads the repaired file's tracks (and motion). Each may refuse with InputError; nothing else.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "fuzz_targets.hpp"
#include "scratch_dir.hpp"
#include "recorded_predictions.hpp"
#include "uavmot/core/error.hpp"
#include "uavmot/mcap/recover.hpp"

namespace uavmot::fuzz {

int recording(const uint8_t* data, size_t size) {
  namespace fs = std::filesystem;
  static const fs::path dir = test_support::fresh_scratch_dir("recording_fuzz");
  const std::string damaged = (dir / "damaged.mcap").string(), repaired = (dir / "repaired.mcap").string();
  std::ofstream(damaged, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  eval::SequenceInfo info;
  info.length = 1000;
  info.width = 640;
  info.height = 480;
  // The damaged file as eval meets it without repair, then repaired.
  for (const std::string& path : {damaged, repaired}) {
    if (path == repaired) {
      try {
        (void)mcap::recover(damaged, repaired);
      } catch (const InputError&) {
        return 0;
      }
    }
    try {
      (void)eval::load_recorded_predictions(path, "", info);
    } catch (const InputError&) {
    }
  }
  return 0;
}

}  // namespace uavmot::fuzz
