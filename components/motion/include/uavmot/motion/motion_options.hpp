#pragma once
// Every parameter of the independent-motion layer (paper section II), with the defaults
// explained in docs/motion.md. Lengths are pixels of the processed frame.

#include <string>

#include "uavmot/core/yaml_config.hpp"

namespace uavmot::motion {

struct MotionOptions {
  // --- Shi-Tomasi detection, only where coverage is missing -------------------------------
  int max_features = 3000;          // cap on live features per frame
  int cell_size_px = 0;             // detection grid cell side; 0 = sized so the cells hold max_features
  int features_per_cell = 1;        // target features per grid cell
  double min_distance_px = 5.0;     // no new corner closer than this to any live feature
  int corner_block_size = 5;        // Shi-Tomasi neighbourhood (px)
  double min_corner_response = 2e-3;  // absolute minimum eigenvalue (cv::cornerMinEigenVal units)
  int border_px = 6;                // features this close to the image border are not used
  int empty_cell_retry_frames = 4;  // a cell that gave no new corner waits this many frames (staggered)

  // --- Pyramidal Lucas-Kanade with forward-backward check ----------------------------------
  int lk_window_px = 11;            // odd window side
  int pyramid_levels = 4;           // levels above the full-resolution image (maxLevel)
  int lk_max_iterations = 20;
  double lk_epsilon_px = 0.01;      // stop when an update is smaller than this
  int backward_levels = 0;          // pyramid levels for the backward check (starts at the answer)
  double max_forward_backward_px = 0.5;
  bool predict_with_previous_homography = true;  // initial flow from the last camera motion
  bool recover_large_motion = true;  // if that fails, retry from a phase-correlation translation
  double max_step_error_px = 3.0;    // a step this far from camera motion + own velocity is a slip (0 = off)

  // --- Frame-to-frame homography ----------------------------------------------------------
  std::string robust_method = "ransac";  // "ransac" or "magsac" (cv::findHomography)
  double ransac_threshold_px = 1.5;
  int ransac_max_iterations = 2000;
  double ransac_confidence = 0.995;
  int min_inliers = 20;             // fewer: the frame is degenerate (flagged invalid)
  double min_inlier_ratio = 0.4;    // of the tracked correspondences
  double min_tracked_ratio = 0.2;   // of the previous frame's features that survived LK + check
  double max_motion_fraction = 0.25;  // image corners may move at most this fraction of the diagonal
  double max_scale_change = 0.2;    // |scale - 1| of the affine part
  bool refine = true;               // Ceres refinement over the inliers
  std::string refine_loss = "cauchy";  // "cauchy", "huber" or "none" (plain least squares)
  double refine_loss_scale_px = 0.3;   // residual where the robust loss starts to bend
  int refine_max_iterations = 15;
  int refine_max_points = 2000;     // inliers thinned evenly to this many: beyond it time grows, accuracy hardly
  bool refine_exclude_moving = true;   // features classified moving do not enter the refinement

  // --- Independent motion ----------------------------------------------------------------
  int background_flow_degree = 3;   // polynomial of the residual background field (0 = off)
  int history_frames = 10;          // positions per feature used for the velocity fit
  int min_track_frames = 2;         // a feature is classified once seen in this many frames
  double position_sigma_px = 0.08;  // prior 1-sigma tracking noise of one position
  double prior_weight = 4.0;        // degrees of freedom the prior noise counts for
  double moving_sigma_factor = 4.0;    // moving when speed > factor * velocity_sigma ...
  double min_moving_speed_px = 0.15;   // ... and > this (px/frame)
  double min_moving_speed_mps = 1.0;   // ... and > this ground speed (m/s, via SceneInfo); 0 = unused
  double scene_noise_factor = 6.0;     // ... and > this times the frame's robust velocity noise (0 = unused)
  double scene_noise_max_px = 0.25;    // ... which counts up to this (px/frame)
  int confirm_frames = 2;           // consecutive significant frames to become moving (and to stop)
  double release_ratio = 0.7;       // a moving feature stops below this fraction of the threshold

  // --- Parallax of static 3-D structure (plane + parallax, docs/motion.md) -------------------
  bool parallax_rejection = true;   // explain motion along the epipolar lines as parallax
  bool parallax_both_sides = true;  // structure on both sides of the homography's plane (real flights: it
                                    // fits a plane between ground and roofs); false: one side only
  int parallax_min_support = 12;    // features on one epipole's lines before it is trusted
  double parallax_min_support_density = 400.0;  // ... and this many per megapixel of image
  double parallax_min_support_fraction = 0.5;  // ... and this share of the features with a clear residual
  double parallax_min_share = 0.15;    // ... and this share of ALL classified features: structure is
                                       // everywhere; movers (which can line up at a junction) are few
  double parallax_min_spread = 0.1;    // ... spread over this fraction of the smaller image side (1-sigma)
  int parallax_stable_frames = 3;      // ... found again, within parallax_stable_angle_deg, this many frames running
  double parallax_stable_angle_deg = 8.0;
  double parallax_across_sigma = 3.0;  // on a line: across-line velocity <= this * sigma + the floor
  double parallax_across_floor_px = 0.05;
  double parallax_max_height_ratio = 0.1;  // tallest structure / flight height above ground: caps the parallax explained
  double parallax_cap_factor = 0.0;    // ... and, when > 0, this times the supporters' median parallax (tighter: misses tall roofs)
  int parallax_ransac_iterations = 300;
};

// Reads a `motion:` section; absent keys keep their defaults. Throws uavmot::InputError naming
// the file, line and key for unknown keys, wrong types and out-of-range values.
MotionOptions load_motion_options(const ConfigNode& node);

// Throws uavmot::InputError when options contradict each other (e.g. an even LK window).
void validate(const MotionOptions& options);

}  // namespace uavmot::motion
