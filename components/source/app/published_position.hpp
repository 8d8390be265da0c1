#pragma once
// Where a source got to, for a respawned one to continue (uavmot source --state-dir): the index of
// the last frame written, one file per stream, replaced atomically after every frame. The process
// may die before that frame reached every reader, so the respawned source sends it again and the
// readers skip what they have (motion: indices it processed; segmentation's pairing: stale ones).

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <optional>
#include <string>

namespace uavmot::source {

inline std::string published_position_file(const std::string& dir, const std::string& stream_id) {
  return dir + "/source_position_" + stream_id + ".txt";
}

inline std::optional<int64_t> load_published_position(const std::string& file) {
  std::ifstream in(file);
  int64_t index = 0;
  if (!(in >> index) || index < 1) return std::nullopt;
  return index;
}

inline bool save_published_position(const std::string& file, int64_t index) {
  const std::string tmp = file + ".tmp";
  {
    std::ofstream out(tmp, std::ios::trunc);
    if (!(out << index << '\n')) return false;
  }
  return std::rename(tmp.c_str(), file.c_str()) == 0;
}

}  // namespace uavmot::source
