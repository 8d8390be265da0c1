#pragma once
// Helpers for tests that launch bringup/local.yaml and disturb it: which pid the launcher gave a
// process, how far the sink's files are, the tracks of a run.

#include <cstdlib>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <opencv2/core/types.hpp>

#include "child_process.hpp"

namespace uavmot::testing {

inline const std::string kLocalProfile = std::string(UAVMOT_SOURCE_DIR) + "/bringup/local.yaml";

// The pid of the latest start of `name` in a launcher's log, or -1.
inline int launched_pid(const std::string& log, const std::string& name) {
  const std::regex started("started " + name + R"( \(pid (\d+)\))");
  int pid = -1;
  for (auto it = std::sregex_iterator(log.begin(), log.end(), started); it != std::sregex_iterator(); ++it) {
    pid = std::stoi((*it)[1]);
  }
  return pid;
}

// The frame of the last complete line of a results file such as tracks_obb.csv (0 before any).
inline int last_frame_written(const std::string& file) {
  const std::string text = read_file(file);
  if (text.size() < 2) return 0;
  const auto start = text.rfind('\n', text.size() - 2);
  return start == std::string::npos ? std::atoi(text.c_str()) : std::atoi(text.c_str() + start + 1);
}

// frame -> id -> box (x, y, w, h), from a MOTChallenge tracks.txt
using TrackTable = std::map<int, std::map<int, cv::Rect2d>>;

inline TrackTable read_tracks(const std::string& file) {
  TrackTable table;
  std::istringstream in(read_file(file));
  for (std::string line; std::getline(in, line);) {
    std::vector<double> v;
    std::stringstream row(line);
    for (std::string cell; std::getline(row, cell, ',');) v.push_back(std::stod(cell));
    table[static_cast<int>(v[0])][static_cast<int>(v[1])] = {v[2], v[3], v[4], v[5]};
  }
  return table;
}

inline double iou(const cv::Rect2d& a, const cv::Rect2d& b) {
  const double inter = (a & b).area();
  return inter / (a.area() + b.area() - inter);
}

}  // namespace uavmot::testing
