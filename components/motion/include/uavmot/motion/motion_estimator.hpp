#pragma once
// The independent-motion layer (paper section II): KLT features tracked frame to frame,
// the frame-to-frame homography (robust estimate refined with Ceres) and, for every feature,
// its velocity relative to the compensated background with a moving/stationary decision.
//
//   uavmot::motion::MotionEstimator motion(options);
//   for (const Frame& frame : frames) { MotionEstimate m = motion.process(frame); ... }
//
// Deterministic: the same frames give bit-identical estimates.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "uavmot/core/chain_types.hpp"
#include "uavmot/core/scene_info.hpp"
#include "uavmot/motion/motion_options.hpp"

namespace uavmot::motion {

// A frame's image pyramid, built ahead by MotionEstimator::prepare (e.g. on a decoding thread).
class PreparedFrame {
 public:
  PreparedFrame();
  ~PreparedFrame();
  PreparedFrame(PreparedFrame&&) noexcept;
  PreparedFrame& operator=(PreparedFrame&&) noexcept;

 private:
  friend class MotionEstimator;
  struct Data;
  std::unique_ptr<Data> data_;
};

// What an estimator did since it was made (diagnostics for logs; not part of the saved state and
// not cleared by reset()): the frames whose feature velocities were decided, those of them in which
// the parallax fit found 3-D structure (its epipole trusted or provisional), and the feature-frames
// that the structure-patch step and the aperture check held still (docs/motion.md).
struct MotionStats {
  int64_t decided_frames = 0;
  int64_t structure_frames = 0;
  int64_t structure_patch_holds = 0;
  int64_t aperture_holds = 0;
};

// One line for logs: whether the frames showed 3-D structure and how much of it was held still,
// and how many feature-frames on lines along their motion were (the in-process chain and the
// motion node say the same).
std::string describe_structure(const MotionStats& stats);

class MotionEstimator {
 public:
  // Throws uavmot::InputError for inconsistent options.
  explicit MotionEstimator(MotionOptions options, SceneInfo scene = {});
  ~MotionEstimator();
  MotionEstimator(MotionEstimator&&) noexcept;
  MotionEstimator& operator=(MotionEstimator&&) noexcept;

  // Frames must be CV_8UC1 (mono8) or CV_8UC3 (bgr8); an empty image or another type throws
  // uavmot::InputError. Degenerate content (blank, saturated, scene cut, huge motion, too few
  // features) never throws: the estimate is flagged invalid with the identity homography, all
  // features restart, and the following frames recover.
  MotionEstimate process(const Frame& frame);

  // The per-frame work that needs none of the estimator's state (the grey image's pyramid), so a
  // pipelined chain can do it on another thread while process() works on the frame before.
  // process(frame, prepare(frame)) gives the same bytes as process(frame). Reads only the
  // options, so it may run beside process(); a frame process() would refuse is left unprepared.
  PreparedFrame prepare(const Frame& frame) const;
  MotionEstimate process(const Frame& frame, PreparedFrame prepared);

  // Forgets all features and the previous frame (e.g. when a stream restarts).
  void reset();

  // Everything the estimator carries from one frame to the next, as bytes: the previous frame's grey
  // image (its pyramid is rebuilt from it, bit for bit), every live feature with its id, age,
  // position history, velocity and moving/static hysteresis, the next feature id, the last
  // homography, the detector's empty-cell back-off and the parallax filter's epipole. Versioned,
  // checksummed and tied to the options (and scene) it was made with. An estimator built with the
  // same options and scene that restore_state()s it and continues gives, frame for frame, the same
  // bytes as the estimator that saved it (docs/motion.md, "Saved state").
  std::vector<uint8_t> save_state() const;
  // Throws uavmot::InputError, leaving the estimator unchanged, for bytes that are not such a
  // state: truncated, corrupt (checksum), another format version, other options, or inconsistent.
  void restore_state(const std::vector<uint8_t>& bytes);
  // The index of the last frame process()ed (or of the restored state's), 0 before any.
  int64_t last_frame_index() const;

  const MotionOptions& options() const;
  const MotionStats& stats() const;

 private:
  class Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace uavmot::motion
