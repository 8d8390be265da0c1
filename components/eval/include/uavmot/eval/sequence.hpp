#pragma once
// Ground truth of one sequence, as `uavmot sim` writes it (docs/sim.md) or recorded in memory
// from the simulator (sim_recorder.hpp).

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core/mat.hpp>
#include <opencv2/core/types.hpp>

#include "uavmot/core/homography.hpp"
#include "uavmot/core/oriented_box.hpp"

namespace uavmot::eval {

struct SequenceInfo {
  std::string name;
  int64_t length = 0;  // frames, numbered 1..length
  int width = 0;
  int height = 0;
  double fps = 25.0;
  double gsd_m = 0.0;  // metres per pixel; 0 = unknown (no metric errors)
};

struct GroundTruthObject {
  int64_t id = 0;
  OrientedBox box;             // oriented box; axis-aligned (angle 0) when only MOT boxes are known
  bool oriented = false;       // true when `box` is a real oriented box
  cv::Rect2d bounds;           // MOTChallenge box: left, top, width, height (continuous)
  bool moving = true;
  bool parked = false;
  double visibility = 1.0;
};

// A static structure (building, tree, wall) in one frame: its silhouette in the image.
struct StructureOutline {
  int64_t id = 0;
  std::string kind;                  // "building", "tree" or "wall"
  std::vector<cv::Point2d> outline;  // convex polygon, image px
};

struct Sequence {
  SequenceInfo info;
  std::map<int64_t, std::vector<GroundTruthObject>> objects;  // frame -> every vehicle in it
  std::map<int64_t, Homography> homographies;                 // frame -> true homography k-1 -> k
  // Per-frame object-id image (CV_32S or CV_16U, 0 = background); empty Mat when unknown.
  std::function<cv::Mat(int64_t frame)> id_mask;
  // Static 3-D structures per frame (gt/structures.csv); has_structures is false for a flat world.
  bool has_structures = false;
  std::map<int64_t, std::vector<StructureOutline>> structures;
};

// Reads seqinfo.ini and gt/ of an MOTChallenge folder written by `uavmot sim`:
// gt/gt_obb.csv (preferred) or gt/all_objects.txt or gt/gt.txt; gt/homographies.txt and
// gt/masks/ and gt/structures.csv when present. Throws InputError naming the file and line on anything malformed.
Sequence load_sequence(const std::string& directory);

// Parses an INI-style seqinfo.ini.
SequenceInfo load_sequence_info(const std::string& seqinfo_file);

}  // namespace uavmot::eval
