// libFuzzer: arbitrary text as the files `uavmot eval` reads (tracks.txt, tracks_obb.csv,
// homographies.txt, features.csv, seqinfo.ini). Bad input must end in InputError, never a crash.

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "uavmot/core/error.hpp"
#include "uavmot/eval/predictions.hpp"
#include "uavmot/eval/sequence.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  static const std::string dir = "/tmp/uavmot_eval_fuzz_" + std::to_string(::getpid());
  std::filesystem::create_directories(dir);
  const std::string text(reinterpret_cast<const char*>(data) + 1, size - 1);
  const std::string file = dir + "/input";
  std::ofstream(file, std::ios::trunc) << text;
  uavmot::eval::SequenceInfo info;
  info.length = 100;
  info.width = 640;
  info.height = 480;
  try {
    uavmot::eval::PredictionFiles files;
    switch (data[0] % 5) {
      case 0: files.tracks = file; break;
      case 1: files.oriented = file; break;
      case 2: files.tracks = file, files.homographies = file; break;
      case 3: files.tracks = file, files.features = file; break;
      default: (void)uavmot::eval::load_sequence_info(file); return 0;
    }
    (void)uavmot::eval::load_predictions(files, info);
  } catch (const uavmot::InputError&) {
  }
  return 0;
}
