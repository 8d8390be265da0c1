#pragma once
// The rows of a tracks_obb.csv that a run wrote (components/core/src/result_files.cpp): every track
// of every frame, whatever its state. One reader for the tests that look inside the file.

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "child_process.hpp"

namespace uavmot::testing {

struct ObbRow {
  int frame = 0;
  int id = 0;
  std::string state;  // tentative, confirmed, coasting, ...
  double cx = 0, cy = 0, width = 0, length = 0, angle_deg = 0, vx = 0, vy = 0;
  double speed_mps = NAN;  // only where the run had a ground sample distance (column speed_mps)
};

// Throws std::runtime_error naming the file and line for a row whose cells do not match the header.
inline std::vector<ObbRow> read_obb_rows(const std::string& file) {
  const auto cells_of = [](const std::string& line) {  // empty cells too (lat,lon of a frame without a mapping)
    std::vector<std::string> cells;
    for (size_t start = 0;;) {
      const size_t comma = line.find(',', start);
      cells.push_back(line.substr(start, comma - start));
      if (comma == std::string::npos) return cells;
      start = comma + 1;
    }
  };
  std::istringstream in(read_file(file));
  std::string line;
  if (!std::getline(in, line)) return {};
  const std::vector<std::string> header = cells_of(line);
  if (header.size() < 10 || header[0] != "frame" || header[9] != "vy") {
    throw std::runtime_error("'" + file + "' has no tracks_obb.csv header: " + line);
  }
  size_t speed_column = 0;
  for (size_t i = 0; i < header.size(); ++i) {
    if (header[i] == "speed_mps") speed_column = i;
  }
  std::vector<ObbRow> rows;
  for (int number = 2; std::getline(in, line); ++number) {
    const std::vector<std::string> c = cells_of(line);
    if (c.size() != header.size()) {
      throw std::runtime_error("'" + file + "' line " + std::to_string(number) + ": " + std::to_string(c.size()) +
                               " cells, the header has " + std::to_string(header.size()));
    }
    ObbRow r;
    r.frame = std::stoi(c[0]);
    r.id = std::stoi(c[1]);
    r.state = c[2];
    r.cx = std::stod(c[3]);
    r.cy = std::stod(c[4]);
    r.width = std::stod(c[5]);
    r.length = std::stod(c[6]);
    r.angle_deg = std::stod(c[7]);
    r.vx = std::stod(c[8]);
    r.vy = std::stod(c[9]);
    if (speed_column > 0) r.speed_mps = std::stod(c[speed_column]);
    rows.push_back(std::move(r));
  }
  return rows;
}

}  // namespace uavmot::testing
