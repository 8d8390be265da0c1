#include "result_files_resume.hpp"

#include <charconv>
#include <fstream>
#include <iterator>
#include <optional>
#include <vector>

#include "uavmot/core/error.hpp"

namespace uavmot::detail {
namespace {
namespace fs = std::filesystem;

struct Line {
  int64_t frame = 0;
  uint64_t end = 0;  // byte offset just past the line's '\n'
  std::string_view text;
};

// The complete lines of a result file after its header (a trailing line without '\n' is dropped).
struct ResultFile {
  std::string content;
  uint64_t header_end = 0;
  std::vector<Line> lines;
};

std::optional<ResultFile> read(const fs::path& path, const std::string* header) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  ResultFile file;
  file.content.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  size_t pos = 0;
  if (header) {
    const size_t eol = file.content.find('\n');
    if (eol == std::string::npos || file.content.compare(0, eol, *header) != 0 || eol != header->size()) {
      throw InputError("cannot continue '" + path.string() + "': its header is not '" + *header +
                       "' (was the run started with other --gsd or --metadata?)");
    }
    pos = file.header_end = eol + 1;
  }
  for (size_t eol; (eol = file.content.find('\n', pos)) != std::string::npos; pos = eol + 1) {
    const std::string_view text(file.content.data() + pos, eol - pos);
    Line line{0, eol + 1, text};
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), line.frame);
    if (ec != std::errc() || end == text.data() + text.size() || *end != ',' || line.frame < 1 ||
        (!file.lines.empty() && line.frame < file.lines.back().frame)) {
      throw InputError("cannot continue '" + path.string() + "': line " + std::to_string(file.lines.size() + (header ? 2 : 1)) +
                       " is not a result line in frame order");
    }
    file.lines.push_back(line);
  }
  return file;
}

int64_t last_frame(const std::optional<ResultFile>& file) {
  return file && !file->lines.empty() ? file->lines.back().frame : 0;
}

// Bytes of FILE up to (and with) its lines of frames <= LIMIT.
uint64_t bytes_through(const ResultFile& file, int64_t limit) {
  uint64_t keep = file.header_end;
  for (const auto& line : file.lines) {
    if (line.frame > limit) break;
    keep = line.end;
  }
  return keep;
}

// The value of column COLUMN (0-based) of a CSV line.
std::string_view column(std::string_view line, int index) {
  for (int i = 0; i < index; ++i) {
    const size_t comma = line.find(',');
    if (comma == std::string_view::npos) return {};
    line.remove_prefix(comma + 1);
  }
  return line.substr(0, line.find(','));
}

}  // namespace

ResumeScan scan_for_resume(const fs::path& dir, bool whole_frames, const std::map<std::string, std::string>& headers) {
  if (fs::exists(dir / "summary.json")) {
    throw InputError("cannot continue the run in '" + dir.string() +
                     "': it has ended (summary.json); write to another folder or remove it");
  }
  std::map<std::string, std::optional<ResultFile>> files;
  for (const char* name : {"homographies.txt", "features.csv", "clusters.txt", "regions.txt", "tracks.txt", "tracks_obb.csv"}) {
    const auto header = headers.find(name);
    files[name] = read(dir / name, header == headers.end() ? nullptr : &header->second);
  }
  ResumeScan scan;
  scan.point.motion_frame = last_frame(files["homographies.txt"]);
  scan.point.segmentation_frame = whole_frames ? scan.point.motion_frame : last_frame(files["regions.txt"]);
  scan.point.tracks_frame = whole_frames ? scan.point.motion_frame : last_frame(files["tracks_obb.csv"]);
  const std::map<std::string, int64_t> limit = {
      {"homographies.txt", scan.point.motion_frame},   {"features.csv", scan.point.motion_frame},
      {"clusters.txt", scan.point.segmentation_frame}, {"regions.txt", scan.point.segmentation_frame},
      {"tracks.txt", scan.point.tracks_frame},         {"tracks_obb.csv", scan.point.tracks_frame}};
  for (const auto& [name, file] : files) {
    if (file) scan.keep_bytes[name] = bytes_through(*file, limit.at(name));
  }
  if (const auto& h = files["homographies.txt"]) {
    for (const auto& line : h->lines) {
      ++scan.frames;
      if (line.text.substr(line.text.find(',')) != ",1,0,0,0,1,0,0,0,1") ++scan.non_identity_homographies;
    }
  }
  if (const auto& obb = files["tracks_obb.csv"]) {
    for (const auto& line : obb->lines) {
      if (line.frame > scan.point.tracks_frame) break;
      if (column(line.text, 2) != "confirmed") continue;
      const std::string_view id = column(line.text, 1);
      uint64_t value = 0;
      if (std::from_chars(id.data(), id.data() + id.size(), value).ec != std::errc()) {
        throw InputError("cannot continue '" + (dir / "tracks_obb.csv").string() + "': a line of frame " +
                         std::to_string(line.frame) + " has no track id");
      }
      scan.confirmed_ids.insert(value);
    }
  }
  return scan;
}

}  // namespace uavmot::detail
