#pragma once
// Writes what the chain produced to the files `uavmot eval` and the MOTChallenge
// tools read. `uavmot process` and the DDS sink both use this one writer, so the
// in-process and distributed chains give byte-identical files.
//
//   tracks.txt       frame,id,bb_left,bb_top,bb_width,bb_height,conf,-1,-1,-1 (confirmed tracks)
//   tracks_obb.csv   frame,id,state,cx,cy,width,length,angle_deg,vx,vy[,metric columns with a GSD]
//   homographies.txt frame,h11..h33 (frame k-1 -> k, h33 = 1; frame 1 is the identity)
//   features.csv     frame,feature_id,x,y,vx,vy,moving
//   clusters.txt     MOTChallenge boxes with id -1
//   regions.txt      MOTChallenge boxes with id -1
//   summary.json     counts and timing

#include <cstdint>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "uavmot/core/chain_types.hpp"
#include "uavmot/core/error.hpp"

namespace uavmot {

struct ResultFilesOptions {
  std::string directory;
  double fps = 25.0;      // frames per second, for speeds
  double gsd_m = 0.0;     // metres per pixel; 0 = unknown (no metric columns)
  bool write_features = true;
  bool write_segmentation = true;
  bool write_clusters = true;  // with write_segmentation; off where clusters are not known (the downlink)
};

struct RunSummary {
  int64_t frames = 0;
  int64_t valid_homographies = 0;
  uint64_t tracks_confirmed = 0;  // distinct confirmed track ids
  double wall_time_s = 0.0;
  std::string input;
  std::map<std::string, double> stage_mean_ms;  // per layer, when known (uavmot process)
};

// A line of regions.txt as printed (printed_fixed with 3 decimals): axis-aligned bounds and
// score. The downlink carries regions in this form, so the ground prints the same bytes.
struct PrintedRegion {
  int64_t x = 0, y = 0, width = 0, height = 0, score = 0;
};
PrintedRegion printed_region(const Region& region);  // throws InvalidArgument for non-finite numbers

class ResultFilesWriter {
 public:
  explicit ResultFilesWriter(ResultFilesOptions options);  // throws InputError if the folder cannot be written
  ~ResultFilesWriter();
  ResultFilesWriter(const ResultFilesWriter&) = delete;
  ResultFilesWriter& operator=(const ResultFilesWriter&) = delete;

  void write_motion(const MotionEstimate& motion);
  void write_segmentation(const SegmentationResult& segmentation);
  // regions.txt only (what the downlink carries of a segmentation).
  void write_printed_regions(int64_t frame_index, const std::vector<PrintedRegion>& regions);
  void write_tracks(const TrackList& tracks);
  // Flushes and writes summary.json; further writes are errors.
  void close(RunSummary summary);

  const ResultFilesOptions& options() const { return options_; }
  int64_t frames_written() const { return frames_; }

 private:
  std::ofstream open(const std::string& name);

  ResultFilesOptions options_;
  std::ofstream tracks_;
  std::ofstream tracks_obb_;
  std::ofstream homographies_;
  std::ofstream features_;
  std::ofstream clusters_;
  std::ofstream regions_;
  std::set<uint64_t> confirmed_ids_;
  int64_t frames_ = 0;
  int64_t valid_homographies_ = 0;
  bool closed_ = false;
};

}  // namespace uavmot
