#include "uavmot/geo/clif_pos.hpp"

#include <charconv>
#include <cmath>
#include <fstream>
#include <vector>

#include "uavmot/core/error.hpp"

namespace uavmot::geo {

namespace {

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r' || s.back() == '\n')) s.remove_suffix(1);
  return s;
}

std::vector<std::string_view> split_fields(std::string_view line) {
  std::vector<std::string_view> fields;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    fields.push_back(trim(line.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start)));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return fields;
}

double number(std::string_view text, const std::string& where, const char* name) {
  double value = 0.0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size() || text.empty() || !std::isfinite(value)) {
    throw InputError(where + ": " + name + " is not a number: '" + std::string(text) + "'");
  }
  return value;
}

int integer(std::string_view text, const std::string& where, const char* name) {
  int value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size() || text.empty()) {
    throw InputError(where + ": " + name + " is not an integer: '" + std::string(text) + "'");
  }
  return value;
}

}  // namespace

ClifPosRecord parse_clif_pos_line(std::string_view line, const std::string& where) {
  const auto fields = split_fields(trim(line));
  if (fields.size() != 14 && fields.size() != 15) {
    throw InputError(where + ": expected 14 or 15 comma-separated POS fields, found " + std::to_string(fields.size()));
  }
  ClifPosRecord r;
  std::size_t i = 0;
  if (fields.size() == 15) r.source_name = std::string(fields[i++]);
  r.yaw_deg = number(fields[i++], where, "yaw");
  r.pitch_deg = number(fields[i++], where, "pitch");
  r.roll_deg = number(fields[i++], where, "roll");
  r.latitude_deg = number(fields[i++], where, "latitude");
  r.longitude_deg = number(fields[i++], where, "longitude");
  r.altitude_ft = number(fields[i++], where, "altitude");
  r.gps_seconds_of_week = number(fields[i++], where, "GPS seconds");
  r.gps_week = integer(fields[i++], where, "GPS week");
  r.north_velocity_mps = number(fields[i++], where, "north velocity");
  r.east_velocity_mps = number(fields[i++], where, "east velocity");
  r.up_velocity_mps = number(fields[i++], where, "up velocity");
  r.imu_status = integer(fields[i++], where, "IMU status");
  r.local_adjustment = integer(fields[i++], where, "local adjustment");
  r.dst_flags = integer(fields[i++], where, "DST flags");
  if (std::abs(r.latitude_deg) > 90.0 || std::abs(r.longitude_deg) > 180.0) {
    throw InputError(where + ": latitude/longitude out of range");
  }
  return r;
}

ClifPosRecord read_clif_pos_file(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path.string() + ": cannot open");
  std::string line;
  if (!std::getline(in, line)) throw InputError(path.string() + ": empty POS file");
  return parse_clif_pos_line(line, path.string() + ":1");
}

}  // namespace uavmot::geo
