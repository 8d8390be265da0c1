// Fuzz target: arbitrary text as each file `uavmot eval` reads: predictions (tracks.txt,
// tracks_obb.csv, homographies.txt, features.csv) and a sequence (seqinfo.ini, gt/gt_obb.csv,
// gt/all_objects.txt, gt/gt.txt, gt/homographies.txt). The first byte picks the file; the
// others of a run are fixed and valid. Bad input must end in InputError, never a crash.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "fuzz_targets.hpp"
#include "scratch_dir.hpp"
#include "uavmot/core/error.hpp"
#include "uavmot/eval/predictions.hpp"
#include "uavmot/eval/sequence.hpp"

namespace uavmot::fuzz {
namespace {

namespace fs = std::filesystem;

void write(const fs::path& path, const std::string& text) { std::ofstream(path, std::ios::trunc) << text; }

// A sequence folder whose `gt/<name>` holds the fuzz text (the other gt files removed).
void load_sequence_with(const fs::path& dir, const std::string& name, const std::string& text) {
  fs::remove_all(dir / "gt");
  fs::create_directories(dir / "gt");
  write(dir / "seqinfo.ini", "[Sequence]\nname=f\nseqLength=100\nimWidth=640\nimHeight=480\nframeRate=25\n");
  if (name == "homographies.txt") write(dir / "gt/gt.txt", "1,1,10,20,5,15,1,1,1\n");
  write(dir / "gt" / name, text);
  (void)eval::load_sequence(dir.string());
}

}  // namespace

int eval_files(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  static const fs::path dir = test_support::fresh_scratch_dir("eval_fuzz");
  const std::string text(reinterpret_cast<const char*>(data) + 1, size - 1);
  const std::string file = (dir / "input").string();
  const std::string tracks = (dir / "tracks.txt").string();
  write(file, text);
  write(tracks, "1,1,10.0,20.0,5.0,15.0,1,-1,-1,-1\n");
  eval::SequenceInfo info;
  info.length = 100;
  info.width = 640;
  info.height = 480;
  try {
    eval::PredictionFiles files;
    switch (data[0] % 9) {
      case 0: files.tracks = file; break;
      case 1: files.oriented = file; break;
      case 2: files.tracks = tracks, files.homographies = file; break;
      case 3: files.tracks = tracks, files.features = file; break;
      case 4: (void)eval::load_sequence_info(file); return 0;
      case 5: load_sequence_with(dir / "seq", "gt_obb.csv", text); return 0;
      case 6: load_sequence_with(dir / "seq", "all_objects.txt", text); return 0;
      case 7: load_sequence_with(dir / "seq", "gt.txt", text); return 0;
      default: load_sequence_with(dir / "seq", "homographies.txt", text); return 0;
    }
    (void)eval::load_predictions(files, info);
  } catch (const InputError&) {
  }
  return 0;
}

}  // namespace uavmot::fuzz
