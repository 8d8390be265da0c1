#include "uavmot/pipeline/chain.hpp"

#include <chrono>

#include "uavmot/motion/motion_estimator.hpp"
#include "uavmot/segmentation/segmenter.hpp"
#include "uavmot/tracking/tracker.hpp"

namespace uavmot::pipeline {

ChainOptions load_chain_options(const std::string& file) { return load_chain_options(config::ChainConfig::load_file(file)); }

ChainOptions load_chain_options(const ConfigNode& root) { return load_chain_options(config::ChainConfig(root)); }

ChainOptions load_chain_options(const config::ChainConfig& config) {
  ChainOptions options;
  options.scene = config.scene;
  options.motion = config.layer("motion", motion::load_motion_options);
  options.segmentation = config.layer("segmentation", segmentation::load_segmentation_options);
  options.tracking = config.layer("tracking", tracking::load_tracker_options);
  return options;
}

struct Chain::Layers {
  explicit Layers(const ChainOptions& o)
      : motion(o.motion, o.scene), segmenter(o.segmentation, o.scene), tracker(o.tracking, o.scene) {}
  motion::MotionEstimator motion;
  segmentation::Segmenter segmenter;
  tracking::Tracker tracker;
};

Chain::Chain(const ChainOptions& options) : layers_(std::make_unique<Layers>(options)) {}
Chain::~Chain() = default;

namespace {
using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }
}  // namespace

ChainOutput Chain::process(const Frame& frame) { return segment_and_track(frame, estimate_motion(frame)); }

motion::PreparedFrame Chain::prepare_motion(const Frame& frame) const { return layers_->motion.prepare(frame); }

MotionEstimate Chain::estimate_motion(const Frame& frame, motion::PreparedFrame prepared) {
  const auto start = Clock::now();
  MotionEstimate motion = layers_->motion.process(frame, std::move(prepared));
  times_.motion_s += seconds_since(start);  // only this half writes motion_s
  return motion;
}

ChainOutput Chain::segment_and_track(const Frame& frame, MotionEstimate motion) {
  ChainOutput out;
  out.motion = std::move(motion);
  auto start = Clock::now();
  out.segmentation = layers_->segmenter.process(frame, out.motion);
  times_.segmentation_s += seconds_since(start);
  if (const auto& shadow = layers_->segmenter.last_stats().shadow_offset_px) {
    ++shadow_frames_;
    for (int axis = 0; axis < 2; ++axis) ++shadow_offset_counts_[axis][(*shadow)[axis]];
  }
  start = Clock::now();
  out.tracks = layers_->tracker.process(out.motion, out.segmentation);
  times_.tracking_s += seconds_since(start);
  ++times_.frames;
  return out;
}

const motion::MotionStats& Chain::motion_stats() const { return layers_->motion.stats(); }

ShadowSummary Chain::shadow_summary() const {
  ShadowSummary summary;
  summary.frames = shadow_frames_;
  // The value at index frames / 2 of the sorted offsets (the upper median of an even count).
  for (int axis = 0; axis < 2; ++axis) {
    int64_t before = 0;
    for (const auto& [offset, count] : shadow_offset_counts_[axis]) {
      if (before + count > shadow_frames_ / 2) {
        summary.median_px[axis] = offset;
        break;
      }
      before += count;
    }
  }
  return summary;
}

}  // namespace uavmot::pipeline
