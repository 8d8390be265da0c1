#pragma once
// MOTChallenge `seqinfo.ini` ([Sequence] name, imDir, frameRate, seqLength, imWidth,
// imHeight, imExt; uavmot adds gsd in metres per pixel).

#include <string>

namespace uavmot::source {

struct SequenceInfo {
  std::string name;
  std::string image_dir = "img1";
  double frame_rate = 25.0;
  int seq_length = 0;
  int width = 0;
  int height = 0;
  std::string image_ext = ".jpg";
  double gsd_m = 0.0;  // 0 when the file does not say
};

bool is_mot_sequence(const std::string& dir);
// Throws InputError naming the file and line for malformed entries.
SequenceInfo read_sequence_info(const std::string& dir);

}  // namespace uavmot::source
