#pragma once
// Writes what the chain produced to the files `uavmot eval` and the MOTChallenge
// tools read. `uavmot process` and the DDS sink both use this one writer, so the
// in-process and distributed chains give byte-identical files.
//
//   tracks.txt       frame,id,bb_left,bb_top,bb_width,bb_height,conf,-1,-1,-1 (confirmed tracks)
//   tracks_obb.csv   frame,id,state,cx,cy,width,length,angle_deg,vx,vy[,metric columns with a GSD]
//                    [,lat,lon with the input's ground geometry]
//   homographies.txt frame,h11..h33 (frame k-1 -> k, h33 = 1; frame 1 is the identity)
//   features.csv     frame,feature_id,x,y,vx,vy,moving
//   clusters.txt     MOTChallenge boxes with id -1
//   regions.txt      MOTChallenge boxes with id -1
//   summary.json     counts and timing
//
// Each call writes its frame's lines to each file with one write(2) and checks it: a full disk
// throws OutputError naming the file and the reason, and every file keeps only complete lines.
// A topic's frame is written with homographies.txt, regions.txt or tracks_obb.csv last, so after
// a crash those mark the last whole frame and a continued run (ResultFilesOptions::resume) cuts
// the other files to it.

#include <cstdint>
#include <array>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "uavmot/core/chain_types.hpp"
#include "uavmot/core/error.hpp"
#include "uavmot/core/output_file.hpp"

namespace uavmot {

// The ground position (latitude, longitude in degrees) of an image point of a frame, or nullopt
// where the frame has no ground mapping. The writer stays free of the geo library: the caller
// (uavmot process, the sink) passes the mapping of the input's flight metadata.
using PixelToLatLon = std::function<std::optional<std::array<double, 2>>(int64_t frame, double x, double y)>;

struct ResultFilesOptions {
  std::string directory;
  double fps = 25.0;      // frames per second, for speeds
  double gsd_m = 0.0;     // metres per pixel; 0 = unknown (no metric columns)
  bool write_features = true;
  bool write_segmentation = true;
  bool write_clusters = true;  // with write_segmentation; off where clusters are not known (the downlink)
  // Continue the unfinished run in `directory` (after a crash or a restart) instead of starting
  // anew: its files keep every whole frame they hold and the new frames follow (resumed_at() says
  // where). InputError when the folder holds a finished run (summary.json) or other columns.
  bool resume = false;
  // With resume: each frame's motion, regions and tracks were written together, homographies.txt
  // last (the downlink sink), so every file is cut to homographies.txt's last frame.
  bool resume_whole_frames = false;
};

// Where a continued run picks up: the last whole frame of each topic in the files. The caller
// skips frames up to these when they arrive again.
struct ResumePoint {
  int64_t motion_frame = 0;        // homographies.txt (features.csv cut to it)
  int64_t segmentation_frame = 0;  // regions.txt (clusters.txt cut to it)
  int64_t tracks_frame = 0;        // tracks_obb.csv (tracks.txt cut to it)
};

// What the input's flight metadata held, for summary.json (docs/geo.md).
struct MetadataSummary {
  int64_t packets = 0;
  std::string standard;  // "EG 0104", "ST 0601" or "ST 0601 + EG 0104"
  int64_t bad_checksums = 0;
  int64_t frames_with_geometry = 0;
};

struct RunSummary {
  int64_t frames = 0;
  int64_t valid_homographies = 0;
  uint64_t tracks_confirmed = 0;  // distinct confirmed track ids
  double wall_time_s = 0.0;
  std::string input;
  std::map<std::string, double> stage_mean_ms;  // per layer, when known (uavmot process)
  std::string gsd_source;  // where gsd_m came from: flag, seqinfo, config, klv, clif_pos, default
  std::optional<MetadataSummary> metadata;
};

// A line of regions.txt as printed (printed_fixed with 3 decimals): axis-aligned bounds and
// score. The downlink carries regions in this form, so the ground prints the same bytes.
struct PrintedRegion {
  int64_t x = 0, y = 0, width = 0, height = 0, score = 0;
};
PrintedRegion printed_region(const Region& region);  // throws InvalidArgument for non-finite numbers

class ResultFilesWriter {
 public:
  // throws InputError if the folder cannot be written. With pixel_to_lat_lon, tracks_obb.csv gets
  // the lat,lon of each box centre.
  explicit ResultFilesWriter(ResultFilesOptions options, PixelToLatLon pixel_to_lat_lon = {});
  ~ResultFilesWriter();
  ResultFilesWriter(const ResultFilesWriter&) = delete;
  ResultFilesWriter& operator=(const ResultFilesWriter&) = delete;

  // Each throws OutputError when a file cannot be written (what was written before stays valid).
  void write_motion(const MotionEstimate& motion);
  void write_segmentation(const SegmentationResult& segmentation);
  // regions.txt only (what the downlink carries of a segmentation).
  void write_printed_regions(int64_t frame_index, const std::vector<PrintedRegion>& regions);
  void write_tracks(const TrackList& tracks);
  // Closes the files and writes summary.json; further writes are errors. Throws OutputError.
  void close(RunSummary summary);

  const ResultFilesOptions& options() const { return options_; }
  int64_t frames_written() const { return frames_; }
  // With ResultFilesOptions::resume: the frames the files already held (all 0 for a new run).
  const ResumePoint& resumed_at() const { return resumed_at_; }

 private:
  OutputFile open(const std::string& name, const std::map<std::string, uint64_t>& keep_bytes);

  ResultFilesOptions options_;
  PixelToLatLon pixel_to_lat_lon_;
  OutputFile tracks_;
  OutputFile tracks_obb_;
  OutputFile homographies_;
  OutputFile features_;
  OutputFile clusters_;
  OutputFile regions_;
  std::set<uint64_t> confirmed_ids_;
  int64_t frames_ = 0;
  int64_t valid_homographies_ = 0;
  ResumePoint resumed_at_;
  bool closed_ = false;
};

}  // namespace uavmot
