#include "uavmot/eval/sequence.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include <fmt/format.h>
#include <opencv2/imgcodecs.hpp>

#include "text_records.hpp"
#include "uavmot/core/error.hpp"

namespace uavmot::eval {
namespace {
namespace fs = std::filesystem;
using detail::fail;
using detail::parse_integer;
using detail::parse_number;

void check_frame(const std::string& file, const detail::Record& r, int64_t frame, const SequenceInfo& info) {
  if (frame < 1 || frame > info.length)
    fail(file, r.line, "frame " + std::to_string(frame) + " is outside the sequence (1.." + std::to_string(info.length) + ")");
}

void add_object(std::map<int64_t, std::vector<GroundTruthObject>>& objects, std::set<std::pair<int64_t, int64_t>>& seen,
                const std::string& file, const detail::Record& r, int64_t frame, GroundTruthObject object) {
  if (object.id < 1) fail(file, r.line, "object id must be at least 1");
  if (!seen.insert({frame, object.id}).second)
    fail(file, r.line, "object " + std::to_string(object.id) + " appears twice in frame " + std::to_string(frame));
  if (!(object.bounds.width > 0.0 && object.bounds.height > 0.0)) fail(file, r.line, "box width and height must be positive");
  objects[frame].push_back(object);
}

void load_oriented(const std::string& file, const SequenceInfo& info, Sequence& seq) {
  const auto records = detail::read_records(file);
  if (records.empty()) return;
  const auto col = detail::header_columns(file, records[0], {"frame", "id", "cx", "cy", "width", "length", "angle_deg", "moving"});
  std::set<std::pair<int64_t, int64_t>> seen;
  for (size_t i = 1; i < records.size(); ++i) {
    const auto& r = records[i];
    const int64_t frame = parse_integer(file, r, col.at("frame"), "frame");
    check_frame(file, r, frame, info);
    GroundTruthObject o;
    o.id = parse_integer(file, r, col.at("id"), "id");
    o.box = {parse_number(file, r, col.at("cx"), "cx"), parse_number(file, r, col.at("cy"), "cy"),
             parse_number(file, r, col.at("width"), "width"), parse_number(file, r, col.at("length"), "length"),
             parse_number(file, r, col.at("angle_deg"), "angle_deg")};
    o.oriented = true;
    o.bounds = axis_aligned_bounds(o.box);
    o.moving = parse_integer(file, r, col.at("moving"), "moving") != 0;
    if (col.count("parked")) o.parked = parse_integer(file, r, col.at("parked"), "parked") != 0;
    if (col.count("visibility")) o.visibility = parse_number(file, r, col.at("visibility"), "visibility");
    add_object(seq.objects, seen, file, r, frame, o);
  }
}

// MOTChallenge-style lines: frame,id,left,top,width,height,a,b,visibility where (a, b) are
// (moving, parked) in all_objects.txt and (consider, class) in gt.txt.
void load_mot(const std::string& file, const SequenceInfo& info, Sequence& seq, bool all_objects) {
  std::set<std::pair<int64_t, int64_t>> seen;
  for (const auto& r : detail::read_records(file)) {
    if (r.fields.size() < 6) fail(file, r.line, "expected at least 6 comma-separated values (frame,id,left,top,width,height)");
    const int64_t frame = parse_integer(file, r, 0, "frame");
    check_frame(file, r, frame, info);
    GroundTruthObject o;
    o.id = parse_integer(file, r, 1, "id");
    o.bounds = {parse_number(file, r, 2, "bb_left"), parse_number(file, r, 3, "bb_top"), parse_number(file, r, 4, "bb_width"),
                parse_number(file, r, 5, "bb_height")};
    o.box = {o.bounds.x + o.bounds.width / 2, o.bounds.y + o.bounds.height / 2, o.bounds.height, o.bounds.width, 0.0};
    if (r.fields.size() > 6) o.moving = parse_number(file, r, 6, all_objects ? "moving" : "conf") != 0.0;
    if (all_objects && r.fields.size() > 7) o.parked = parse_number(file, r, 7, "parked") != 0.0;
    if (r.fields.size() > 8) o.visibility = parse_number(file, r, 8, "visibility");
    add_object(seq.objects, seen, file, r, frame, o);
  }
}

// frame,id,kind,...,outline with the outline as "x y x y ..." (at least three points).
void load_structures(const std::string& file, const SequenceInfo& info, Sequence& seq) {
  const auto records = detail::read_records(file);
  seq.has_structures = true;
  if (records.empty()) return;
  const auto col = detail::header_columns(file, records[0], {"frame", "id", "kind", "outline"});
  for (size_t i = 1; i < records.size(); ++i) {
    const auto& r = records[i];
    if (r.fields.size() != records[0].fields.size()) fail(file, r.line, "expected " + std::to_string(records[0].fields.size()) + " columns");
    const int64_t frame = parse_integer(file, r, col.at("frame"), "frame");
    check_frame(file, r, frame, info);
    StructureOutline s;
    s.id = parse_integer(file, r, col.at("id"), "id");
    s.kind = r.fields[col.at("kind")];
    if (s.kind != "building" && s.kind != "tree" && s.kind != "wall")
      fail(file, r.line, "kind '" + s.kind + "' is not building, tree or wall");
    std::istringstream numbers(r.fields[col.at("outline")]);
    std::vector<double> xy;
    std::string token;
    while (numbers >> token) {
      char* end = nullptr;
      const double v = std::strtod(token.c_str(), &end);
      if (*end != '\0' || !std::isfinite(v)) fail(file, r.line, "outline value '" + token + "' is not a finite number");
      xy.push_back(v);
    }
    if (xy.size() < 6 || xy.size() % 2 != 0) fail(file, r.line, "outline needs at least three x y points");
    for (size_t k = 0; k < xy.size(); k += 2) s.outline.emplace_back(xy[k], xy[k + 1]);
    seq.structures[frame].push_back(std::move(s));
  }
}

}  // namespace

SequenceInfo load_sequence_info(const std::string& file) {
  std::ifstream in(file);
  if (!in) throw InputError("cannot open '" + file + "' (is this an MOTChallenge sequence folder?)");
  std::map<std::string, std::string> values;
  std::string line;
  while (std::getline(in, line)) {
    const size_t eq = line.find('=');
    if (eq == std::string::npos) continue;
    auto trim = [](std::string s) {
      const size_t a = s.find_first_not_of(" \t\r");
      const size_t b = s.find_last_not_of(" \t\r");
      return a == std::string::npos ? std::string() : s.substr(a, b - a + 1);
    };
    values[trim(line.substr(0, eq))] = trim(line.substr(eq + 1));
  }
  // `max` keeps the integer casts below defined (a value beyond the target type is undefined).
  const auto number = [&](const char* key, bool required, double fallback, double max) {
    auto it = values.find(key);
    if (it == values.end()) {
      if (required) throw InputError(file + ": missing '" + key + "'");
      return fallback;
    }
    char* end = nullptr;
    const double v = std::strtod(it->second.c_str(), &end);
    if (it->second.empty() || *end != '\0' || !std::isfinite(v) || v < 0)
      throw InputError(file + ": '" + key + "' is not a valid number: '" + it->second + "'");
    if (v > max) throw InputError(file + ": '" + key + "' is larger than " + fmt::format("{:g}", max) + ": '" + it->second + "'");
    return v;
  };
  constexpr double kMaxFrames = 1e9;
  constexpr double kMaxSide = 1 << 20;
  SequenceInfo info;
  info.name = values.count("name") ? values["name"] : fs::path(file).parent_path().filename().string();
  info.length = static_cast<int64_t>(number("seqLength", true, 0, kMaxFrames));
  info.width = static_cast<int>(number("imWidth", true, 0, kMaxSide));
  info.height = static_cast<int>(number("imHeight", true, 0, kMaxSide));
  info.fps = number("frameRate", false, 25.0, 1e6);
  info.gsd_m = number("gsd", false, 0.0, 1e6);
  if (info.length < 1) throw InputError(file + ": seqLength must be at least 1");
  return info;
}

Sequence load_sequence(const std::string& directory) {
  const fs::path dir(directory);
  if (!fs::is_directory(dir)) throw InputError("sequence folder '" + directory + "' does not exist");
  Sequence seq;
  seq.info = load_sequence_info((dir / "seqinfo.ini").string());
  const fs::path gt = dir / "gt";
  if (fs::exists(gt / "gt_obb.csv")) {
    load_oriented((gt / "gt_obb.csv").string(), seq.info, seq);
  } else if (fs::exists(gt / "all_objects.txt")) {
    load_mot((gt / "all_objects.txt").string(), seq.info, seq, true);
  } else if (fs::exists(gt / "gt.txt")) {
    load_mot((gt / "gt.txt").string(), seq.info, seq, false);
  } else {
    throw InputError("'" + directory + "' has no ground truth (gt/gt_obb.csv, gt/all_objects.txt or gt/gt.txt)");
  }
  if (fs::exists(gt / "homographies.txt")) seq.homographies = detail::read_homographies((gt / "homographies.txt").string(), seq.info.length);
  if (fs::exists(gt / "structures.csv")) load_structures((gt / "structures.csv").string(), seq.info, seq);
  if (fs::is_directory(gt / "masks")) {
    const std::string masks = (gt / "masks").string();
    seq.id_mask = [masks](int64_t frame) {
      const std::string path = masks + "/" + fmt::format("{:06d}.png", frame);
      if (!fs::exists(path)) return cv::Mat();
      cv::Mat mask = cv::imread(path, cv::IMREAD_UNCHANGED);
      if (mask.empty() || mask.channels() != 1) throw InputError("cannot read the id mask '" + path + "'");
      return mask;
    };
  }
  return seq;
}

}  // namespace uavmot::eval
