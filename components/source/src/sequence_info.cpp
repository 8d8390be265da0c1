#include "uavmot/source/sequence_info.hpp"

#include <filesystem>
#include <fstream>

#include "uavmot/core/error.hpp"

namespace uavmot::source {
namespace {
std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r");
  const auto e = s.find_last_not_of(" \t\r");
  return b == std::string::npos ? "" : s.substr(b, e - b + 1);
}
}  // namespace

bool is_mot_sequence(const std::string& dir) {
  return std::filesystem::is_regular_file(std::filesystem::path(dir) / "seqinfo.ini");
}

SequenceInfo read_sequence_info(const std::string& dir) {
  const auto path = (std::filesystem::path(dir) / "seqinfo.ini").string();
  std::ifstream in(path);
  if (!in) throw InputError("cannot read '" + path + "'");
  SequenceInfo info;
  std::string line;
  int line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    line = trim(line);
    if (line.empty() || line[0] == ';' || line[0] == '#' || line[0] == '[') continue;
    const auto eq = line.find('=');
    if (eq == std::string::npos) throw InputError(path + ":" + std::to_string(line_number) + ": expected key=value");
    const std::string key = trim(line.substr(0, eq));
    const std::string value = trim(line.substr(eq + 1));
    try {
      if (key == "name") info.name = value;
      else if (key == "imDir") info.image_dir = value;
      else if (key == "frameRate") info.frame_rate = std::stod(value);
      else if (key == "seqLength") info.seq_length = std::stoi(value);
      else if (key == "imWidth") info.width = std::stoi(value);
      else if (key == "imHeight") info.height = std::stoi(value);
      else if (key == "imExt") info.image_ext = value;
      else if (key == "gsd") info.gsd_m = std::stod(value);
    } catch (const std::exception&) {
      throw InputError(path + ":" + std::to_string(line_number) + ": '" + key + "' has a malformed value '" + value + "'");
    }
  }
  if (!(info.frame_rate > 0.0)) throw InputError(path + ": frameRate must be positive");
  return info;
}

}  // namespace uavmot::source
