#pragma once
// Reading frames from a video file, an image folder or an MOTChallenge sequence.
//
//   auto source = open_frame_source({.path = "seq/"});
//   Frame frame;
//   while (source->next(frame)) { ... }
//
// Frames are numbered from 1 in the order of the input (after `start_frame`).

#include <cstdint>
#include <memory>
#include <string>

#include <opencv2/core/types.hpp>

#include "uavmot/core/chain_types.hpp"

namespace uavmot::source {

enum class ColorMode { Gray, Color };

struct FrameSourceOptions {
  std::string path;                // video file, image folder, or MOTChallenge sequence folder
  std::string stream_id = "uav1";  // key of every sample this stream produces
  int64_t start_frame = 1;         // first input frame to deliver (1-based)
  int64_t max_frames = 0;          // 0 = all
  bool loop = false;               // start again at start_frame after the last frame
  ColorMode color = ColorMode::Gray;
  bool skip_corrupt = false;       // skip unreadable images with a warning instead of failing
  double fps_override = 0.0;       // 0 = the input's own rate (or 25 for image folders)
};

struct SourceInfo {
  std::string kind;         // "video", "images" or "mot"
  double fps = 25.0;
  cv::Size size;            // size of the first frame
  int64_t frame_count = 0;  // frames the source will deliver (before looping), 0 if unknown
  double gsd_m = 0.0;       // from seqinfo.ini `gsd`, 0 if unknown
};

class FrameSource {
 public:
  virtual ~FrameSource() = default;
  // Fills `frame` and returns true, or returns false at the end of the input.
  // Throws InputError when the input is corrupt (the message names the file).
  virtual bool next(Frame& frame) = 0;
  // Passes over the next frame without decoding it (live mode: a frame the source is too late
  // for) and returns true, or returns false at the end of the input. Its index is used up, so the
  // frames after it keep their input numbering (and their capture times).
  virtual bool skip() = 0;
  virtual const SourceInfo& info() const = 0;
  // Frames skipped because they could not be decoded (skip_corrupt mode).
  virtual int64_t skipped() const = 0;
};

// Detects the kind of input; throws InputError for a missing, empty or unreadable input.
std::unique_ptr<FrameSource> open_frame_source(const FrameSourceOptions& options);

ColorMode parse_color_mode(const std::string& name);  // "gray" or "color"

}  // namespace uavmot::source
