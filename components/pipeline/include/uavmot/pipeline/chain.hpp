#pragma once
// The whole chain in one process: motion -> segmentation -> tracking, called in the same order
// and with the same data as the distributed chain, so both give the same tracks (paper Fig. 1).

#include <array>
#include <map>
#include <memory>
#include <string>

#include <opencv2/core/matx.hpp>

#include "uavmot/config/chain_config.hpp"
#include "uavmot/core/chain_types.hpp"
#include "uavmot/core/scene_info.hpp"
#include "uavmot/core/yaml_config.hpp"
#include "uavmot/motion/motion_estimator.hpp"
#include "uavmot/motion/motion_options.hpp"
#include "uavmot/segmentation/segmentation_options.hpp"
#include "uavmot/tracking/tracker_options.hpp"

namespace uavmot::pipeline {

struct ChainOptions {
  SceneInfo scene;
  motion::MotionOptions motion;
  segmentation::SegmentationOptions segmentation;
  tracking::TrackerOptions tracking;
};

// Reads a chain configuration (sections scene, motion, segmentation, tracking; all optional), every
// section of it. Throws InputError naming the file, line and key of anything invalid.
ChainOptions load_chain_options(const std::string& file);
ChainOptions load_chain_options(const ConfigNode& root);
ChainOptions load_chain_options(const config::ChainConfig& config);

struct ChainOutput {
  MotionEstimate motion;
  SegmentationResult segmentation;
  TrackList tracks;
};

// Wall time spent in each layer, summed over the frames processed (for summary.json and logs).
struct StageTimes {
  int64_t frames = 0;
  double motion_s = 0.0, segmentation_s = 0.0, tracking_s = 0.0;
};

// The vehicles' shadow offset the segmentation took out of its boxes (docs/segmentation.md,
// "Shadows"): in how many frames, and the median offset over them (image px).
struct ShadowSummary {
  int64_t frames = 0;
  cv::Vec2d median_px{0.0, 0.0};
};

class Chain {
 public:
  explicit Chain(const ChainOptions& options);
  ~Chain();
  Chain(const Chain&) = delete;
  Chain& operator=(const Chain&) = delete;

  ChainOutput process(const Frame& frame);

  // process() in three parts, for the pipelined run (chain_runner.hpp): the frame's pyramid on the
  // decoding thread, motion of frame k+1 on one thread, segmentation and tracking of frame k on
  // another. prepare_motion has no state; the other two keep their own and must get the frames in
  // order, each from one thread at a time. Same bytes as process().
  motion::PreparedFrame prepare_motion(const Frame& frame) const;
  MotionEstimate estimate_motion(const Frame& frame, motion::PreparedFrame prepared = {});
  ChainOutput segment_and_track(const Frame& frame, MotionEstimate motion);

  // Read after the threads calling the halves have finished.
  const StageTimes& stage_times() const { return times_; }
  ShadowSummary shadow_summary() const;
  const motion::MotionStats& motion_stats() const;

 private:
  struct Layers;
  std::unique_ptr<Layers> layers_;
  StageTimes times_;
  // How often each shadow offset (per axis) was taken out of a frame's boxes: the offsets lie on the
  // estimator's candidate grid, so a run of any length keeps at most a few hundred counts.
  std::array<std::map<double, int64_t>, 2> shadow_offset_counts_;
  int64_t shadow_frames_ = 0;
};

}  // namespace uavmot::pipeline
