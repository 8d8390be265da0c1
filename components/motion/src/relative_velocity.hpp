#pragma once
// Velocity of a feature relative to the compensated background, from its track history.
//
// Each feature keeps its recent positions mapped into the CURRENT frame through the chain of
// frame-to-frame homographies. A background point then sits still (all positions coincide);
// an independently moving one lies on a line whose slope is its velocity in px/frame. A least
// squares line fit over the window gives the velocity, and its residual, shrunk towards a prior
// tracking noise, gives the 1-sigma noise of that velocity.

#include <utility>
#include <vector>

#include <opencv2/core/matx.hpp>
#include <opencv2/core/types.hpp>

#include "uavmot/core/homography.hpp"
#include "uavmot/motion/motion_options.hpp"

namespace uavmot::motion {

struct VelocityEstimate {
  cv::Vec2d velocity{0.0, 0.0};  // px/frame in the current frame
  double sigma = 0.0;            // 1-sigma of each velocity component (px/frame)
  bool available = false;        // false with fewer than 2 positions
};

class FeatureHistory {
 public:
  // Maps every stored position through `h` (previous frame -> current frame).
  void carry_forward(const Homography& h);
  // Appends the current position, keeping at most `capacity` positions.
  void push(const cv::Point2f& position, int capacity);
  int size() const { return static_cast<int>(positions_.size()); }
  const std::vector<cv::Point2d>& positions() const { return positions_; }
  // Replaces the positions (restoring a saved estimator state).
  void restore(std::vector<cv::Point2d> positions) { positions_ = std::move(positions); }

 private:
  // Oldest first, the last is the current position. A vector, not a deque: a feature is moved
  // several times a frame, and libstdc++'s deque allocates on every move (13 800 allocations per
  // 1080p frame); dropping the oldest of at most history_frames positions shifts a few bytes.
  std::vector<cv::Point2d> positions_;
};

VelocityEstimate estimate_velocity(const FeatureHistory& history, const MotionOptions& options);

// A step from `from` (previous frame) to `to` that lands more than `max_step_error_px` from where the
// camera motion `h` and the feature's known velocity put it: the LK window latched onto another corner
// (often near the border), which is no motion. False while the velocity is unknown or the check is off (0).
bool is_tracking_slip(const Homography& h, const cv::Point2f& from, const cv::Point2f& to, const VelocityEstimate& known,
                      double max_step_error_px);

// The frame's own noise: scene_noise_factor times the robust 1-sigma of the velocity components of
// all classified features (median speed / 1.1774, the median of a 2-D Gaussian's norm). Each
// feature's sigma comes from its own line fit, which misses slow drifts that real imagery has
// (JPEG, appearance change, shimmering trees); the whole frame's spread does not. Moving objects
// are few, so the median ignores them. At most scene_noise_max_px: a frame whose whole field is
// off (a fast turn the velocity fits lag behind) must not hide every vehicle. 0 when off or with
// fewer than 20 speeds.
double scene_noise_floor(std::vector<double> speeds, const MotionOptions& options);

// Moving/stationary decision with hysteresis: a feature becomes moving after confirm_frames
// consecutive frames with a significant speed (> max(moving_sigma_factor * sigma,
// min_moving_speed_px, the scene noise floor)), or at its first decision (seen in exactly
// min_track_frames frames) when above strong_motion_factor times that threshold, and stops after
// confirm_frames consecutive frames below release_ratio times the threshold. Features seen in fewer
// than min_track_frames frames are stationary.
class MotionClassifier {
 public:
  // `floor_px`: a lower bound on the threshold from the whole frame's noise (scene_noise_floor()).
  bool update(const VelocityEstimate& estimate, int track_frames, const MotionOptions& options, double floor_px = 0.0);
  bool moving() const { return moving_; }
  int streak() const { return streak_; }
  // Restores a saved state (moving(), streak()).
  void restore(bool moving, int streak) {
    moving_ = moving;
    streak_ = streak;
  }

 private:
  bool moving_ = false;
  int streak_ = 0;  // consecutive frames arguing for a change of state
};

}  // namespace uavmot::motion
