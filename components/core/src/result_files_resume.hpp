#pragma once
// What an unfinished run left in a result folder, for ResultFilesWriter to continue it: each file
// cut to whole frames of its topic, and the counts summary.json needs of the frames before.
// Each topic's frame is written with its "marker" file last (homographies.txt for motion,
// regions.txt for segmentation, tracks_obb.csv for tracks), so the marker's last frame is the
// topic's last whole frame and the other files of the topic are cut to it.

#include <cstdint>
#include <filesystem>
#include <map>
#include <set>
#include <string>

#include "uavmot/core/result_files.hpp"

namespace uavmot::detail {

struct ResumeScan {
  ResumePoint point;
  std::map<std::string, uint64_t> keep_bytes;  // file name -> bytes to keep (absent: start it anew)
  int64_t frames = 0;                          // lines of homographies.txt kept
  int64_t non_identity_homographies = 0;       // summary.json's valid_homographies of those frames
  std::set<uint64_t> confirmed_ids;            // in tracks_obb.csv's kept lines
};

// Throws InputError when DIR holds a finished run (summary.json), or a file whose header is not
// HEADERS' (file name -> header line; other options wrote it) or whose lines are no result lines.
ResumeScan scan_for_resume(const std::filesystem::path& dir, bool whole_frames,
                           const std::map<std::string, std::string>& headers);

}  // namespace uavmot::detail
