#pragma once
// Every parameter of the independent-motion layer (paper section II), with the defaults
// explained in docs/motion.md. Lengths are pixels of the processed frame.

#include <initializer_list>
#include <string>

#include "uavmot/core/scene_info.hpp"
#include "uavmot/core/yaml_config.hpp"

namespace uavmot::motion {

struct MotionOptions {
  // --- Shi-Tomasi detection, only where coverage is missing -------------------------------
  int max_features = 3000;          // cap on live features per frame
  int cell_size_px = 0;             // detection grid cell side; 0 = sized so the cells hold max_features
  int features_per_cell = 1;        // target features per grid cell
  double min_distance_px = 5.0;     // no new corner closer than this to any live feature
  int corner_block_size = 5;        // Shi-Tomasi neighbourhood (px)
  double min_corner_response = 2e-3;  // minimum eigenvalue (cv::cornerMinEigenVal units) at full contrast
  // Low contrast (haze, a dim sensor, dark cars on dark asphalt) weakens every corner by the square
  // of the contrast: in a frame whose 99th-percentile gradient is below contrast_reference_grey
  // (grey levels per pixel) min_corner_response counts (gradient / reference)^2 of itself, at least
  // contrast_min_scale. 0 = off.
  double contrast_reference_grey = 26.0;
  double contrast_min_scale = 0.5;
  // In such a frame a feature not yet moving whose LK window has faded below this x the frame's
  // corner threshold (noise on a weak corner, an edge it slides along) does not start moving. 0 = off.
  double faded_corner_ratio = 0.5;
  // Features this close to the image border are not used: 5 keeps the 11 x 11 LK window inside it.
  int border_px = 5;
  // ... nor this close to a black band at the image's edge (analogue capture, letterboxing): lines
  // from an edge inward with mean grey at most this (and no pixel above 4 x this) are not picture,
  // at most an eighth of each side (active_picture.hpp). 0 = the whole image is picture.
  double blank_band_max_grey = 12.0;
  int empty_cell_retry_frames = 4;  // a cell that gave no new corner waits this many frames (staggered)
  // ... or fewer: only until the camera has moved the image at the cell by this many cells (at its
  // present rate), since the cell then shows new ground. A fast camera (`fastcam`, a cell's width
  // per frame) uncovers vehicles that a 4-frame wait left unseen. 0 = the frame count only.
  double empty_cell_retry_shift_cells = 1.0;
  // A frame left with fewer than sparse_features_fraction x max_features live features (blur from
  // a fast camera over fields or water) cannot hold the homography on the ground: every cell that
  // lacks features is searched again at sparse_response_factor x min_corner_response.
  double sparse_features_fraction = 0.05;
  double sparse_response_factor = 0.25;  // 1 = off
  // Features seeded on change: corners on pixels that differ from the previous frame warped by the
  // homography (something moves there) are added first, even in cells that hold enough features
  // and when max_features is reached: at most this many per frame, change_features_per_cell per
  // cell; 0 = off. Only where a car (SceneInfo) is shorter than change_seed_max_car_cells detection
  // cells: there a car fits in a cell that a ground corner already fills; a longer car spans free
  // cells and gets corners from the grid (real FMV at 5 cm/px gained only false boxes; 0 = always).
  int change_seed_features = 300;
  double change_seed_max_car_cells = 2.0;
  int change_features_per_cell = 2;
  double change_threshold_sigma = 4.0;  // changed: |difference| above this many robust sigmas ...
  double change_min_grey = 12.0;        // ... and above this many grey levels
  // A changed blob (8-connected) whose bounding box is longer than this many vehicle lengths
  // (SceneInfo) on either side is not a vehicle (a car's change is its front and back edges, within
  // its length plus its step) but 3-D structure under parallax, a long thin edge: no seeds there. 0 = off.
  double change_max_extent_lengths = 3.0;
  // The frame difference is taken on the half-size pyramid level when a car (SceneInfo) is still
  // this many pixels wide there: at 1080p and 0.3 m/px, a quarter of the work.
  double change_min_vehicle_width_px = 3.0;

  // --- Pyramidal Lucas-Kanade with forward-backward check ----------------------------------
  // Odd window side, or 0 (the default): from the scene, 11 unless cars are shorter than about
  // 12 px, then smaller (automatic_lk_window_px), so that a small car's corners are not tracked
  // with the ground around them.
  int lk_window_px = 0;
  int pyramid_levels = 4;           // levels above the full-resolution image (maxLevel)
  // Levels of a frame's first tracking attempt, from the predicted positions: the prediction is
  // within a few pixels in smooth flight, and the coarse levels cost as much per feature as the
  // fine ones. A frame whose attempt gives no valid homography (a jump, dropped frames) is tracked
  // again with all pyramid_levels.
  int lk_quick_levels = 2;
  int lk_max_iterations = 20;
  double lk_epsilon_px = 0.01;      // stop when an update is smaller than this
  int backward_levels = 0;          // pyramid levels for the backward check (starts at the answer)
  double max_forward_backward_px = 0.5;
  bool predict_with_previous_homography = true;  // initial flow from the last camera motion
  bool recover_large_motion = true;  // if that fails, retry from a phase-correlation translation
  double max_step_error_px = 3.0;    // a step this far from camera motion + own velocity is a slip (0 = off)
  // A corner beside a vehicle whose LK window is mostly vehicle moves with it while its centre is
  // ground: once classified moving it is dropped when its centre patch matches the ground's
  // previous place (the homography) better than dragged_ratio x its own track's (0 = off).
  double dragged_ratio = 0.5;
  int dragged_patch_radius_px = 2;     // the centre patch is (2 r + 1)^2 pixels
  double dragged_min_difference = 2.0; // RMS grey levels of the own track's mismatch below which nothing is decided
  // A feature whose centre patch (dragged_patch_radius_px) holds less than this share of its
  // gradient energy along its motion (a lane marking beside a car, a roof's edge: the aperture
  // problem) does not move this frame: what moves it is the rest of its window (dragged_feature.hpp).
  // 0 = off. Only where a car (SceneInfo) is at least aperture_min_car_px long: a car a few LK windows
  // long shows corners besides its sides, while a 13 px uniform car may show nothing but its side
  // edges (`paper` -0.6 points with the check everywhere; on the 5 cm/px aphill FMV, false boxes on
  // roofs 22 -> 4). 0 = at any size.
  double aperture_ratio = 0.1;
  double aperture_min_car_px = 40.0;

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
  // In a frame where the parallax fit finds no 3-D structure (its model neither trusted nor
  // provisional) the pixel floor counts this much (the ground-speed floor stays whole): what it
  // guards against most is parallax. 1 = off.
  double flat_scene_speed_factor = 0.8;
  // ... and a feature may count as moving down to creep_speed_factor x that floor (the ground-speed
  // floor too), but at most creep_max_drop_px below it, when no feature within creep_neighbour_lengths
  // vehicle lengths moves more than creep_neighbour_ratio times as fast its way: a car creeping in a
  // queue, not a ground corner dragged by a passing one (creeping_features.hpp). The neighbours tell
  // nothing about parallax or a parked car's changing look, which on real video reach a few tenths
  // of a pixel per frame: hence the drop's bound. Not in low-contrast frames. 1 = off.
  double creep_speed_factor = 0.5;
  double creep_max_drop_px = 0.05;
  double creep_neighbour_lengths = 1.0;
  double creep_neighbour_ratio = 1.5;
  int creep_min_support = 2;  // ... and with this many candidates (itself included) going its way near it
  double scene_noise_factor = 6.0;     // ... and > this times the frame's robust velocity noise (0 = unused)
  double scene_noise_max_px = 0.25;    // ... which counts up to this (px/frame)
  int confirm_frames = 2;           // consecutive significant frames to become moving (and to stop)
  // ... except that a new feature whose first velocity is above this many times the threshold is
  // moving at once: a car that has just come into view is found a frame earlier. Not in a
  // low-contrast frame nor in one where the parallax fit found 3-D structure. 0 = off.
  double strong_motion_factor = 2.0;
  // ... and only where that frame matters: where the camera carries the ground across the image's
  // smaller side in at most this many frames, so a car is in view for little time (fastcam: 29).
  // Under a slow camera a frame of latency costs almost nothing, and on real FMV (aphill_short,
  // 0.4 px/frame) strong starts were false tracks at the image border (docs/motion.md). 0 = always.
  double strong_motion_max_view_frames = 60.0;
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
  int parallax_startup_frames = 20;    // in the first this many frames, a model short of the density or stability explains too (0 = off)
  double parallax_stable_angle_deg = 8.0;
  double parallax_across_sigma = 3.0;  // on a line: across-line velocity <= this * sigma + the floor
  double parallax_across_floor_px = 0.05;
  double parallax_max_height_ratio = 0.1;  // tallest structure / flight height above ground: caps the parallax explained
  double parallax_cap_factor = 0.0;    // ... and, when > 0, this times the supporters' median parallax (tighter: misses tall roofs)
  int parallax_ransac_iterations = 300;
  // Corners on the silhouette of structure (a roof edge over ground texture slide off their
  // epipolar line): a feature that is not moving yet, has at least parallax_edge_min_supporters
  // structure supporters within parallax_edge_radius_px and is no faster than
  // parallax_edge_speed_factor x the parallax cap there does not start moving (0 radius: off).
  double parallax_edge_radius_px = 24.0;
  int parallax_edge_min_supporters = 3;
  double parallax_edge_speed_factor = 1.5;
  // A candidate's own pixels, where the epipole is trusted: it does not move this frame when its
  // patch is explained about as well by static structure (the previous frame shifted along the
  // epipolar line, 0 to the cap) as by its own track: the mean over the patch of each pixel's best
  // structure shift is at most structure_patch_ratio x the same for the track (structure_patch.hpp;
  // 0 = off).
  double structure_patch_ratio = 1.0;
  int structure_patch_radius_px = 3;  // the patch is (2 r + 1)^2 pixels
};

// The limits of one option in the configuration file.
template <class T>
struct Range {  // a number in [low, high]
  T low, high;
};
struct Flag {};  // true or false
struct Choices {  // one of these words
  std::initializer_list<const char*> names;
};

// Every option of MotionOptions, once, as visit(key, field, limits): the configuration file's keys
// (load_motion_options) and the saved state's options fingerprint (MotionEstimator::save_state)
// both go through this list, so an option added here is read and guards the saved state, and one
// left out is caught by the tests (motion_options_test.cpp). OPTIONS is MotionOptions or
// const MotionOptions. In the order of the struct, which is the order the fingerprint hashes.
template <class Options, class Visit>
void for_each_motion_option(Options& o, Visit&& visit) {
  visit("max_features", o.max_features, Range<int>{10, 100000});
  visit("cell_size_px", o.cell_size_px, Range<int>{0, 1024});  // 0 or >= 8: load_motion_options
  visit("features_per_cell", o.features_per_cell, Range<int>{1, 64});
  visit("min_distance_px", o.min_distance_px, Range<double>{1.0, 256.0});
  visit("corner_block_size", o.corner_block_size, Range<int>{3, 15});
  visit("min_corner_response", o.min_corner_response, Range<double>{0.0, 1.0});
  visit("contrast_reference_grey", o.contrast_reference_grey, Range<double>{0.0, 255.0});
  visit("contrast_min_scale", o.contrast_min_scale, Range<double>{0.0, 1.0});
  visit("faded_corner_ratio", o.faded_corner_ratio, Range<double>{0.0, 10.0});
  visit("border_px", o.border_px, Range<int>{0, 256});
  visit("blank_band_max_grey", o.blank_band_max_grey, Range<double>{0.0, 63.0});
  visit("empty_cell_retry_frames", o.empty_cell_retry_frames, Range<int>{1, 1000});
  visit("empty_cell_retry_shift_cells", o.empty_cell_retry_shift_cells, Range<double>{0.0, 1000.0});
  visit("sparse_features_fraction", o.sparse_features_fraction, Range<double>{0.0, 1.0});
  visit("sparse_response_factor", o.sparse_response_factor, Range<double>{0.0, 1.0});
  visit("change_seed_features", o.change_seed_features, Range<int>{0, 100000});
  visit("change_seed_max_car_cells", o.change_seed_max_car_cells, Range<double>{0.0, 1000.0});
  visit("change_features_per_cell", o.change_features_per_cell, Range<int>{1, 64});
  visit("change_threshold_sigma", o.change_threshold_sigma, Range<double>{0.0, 100.0});
  visit("change_min_grey", o.change_min_grey, Range<double>{0.0, 255.0});
  visit("change_max_extent_lengths", o.change_max_extent_lengths, Range<double>{0.0, 100.0});
  visit("change_min_vehicle_width_px", o.change_min_vehicle_width_px, Range<double>{0.5, 1000.0});
  visit("lk_window_px", o.lk_window_px, Range<int>{0, 63});  // 0 or odd >= 5: load_motion_options
  visit("pyramid_levels", o.pyramid_levels, Range<int>{0, 6});
  visit("lk_quick_levels", o.lk_quick_levels, Range<int>{0, 6});
  visit("lk_max_iterations", o.lk_max_iterations, Range<int>{1, 200});
  visit("lk_epsilon_px", o.lk_epsilon_px, Range<double>{1e-5, 1.0});
  visit("backward_levels", o.backward_levels, Range<int>{0, 6});
  visit("max_forward_backward_px", o.max_forward_backward_px, Range<double>{0.01, 10.0});
  visit("predict_with_previous_homography", o.predict_with_previous_homography, Flag{});
  visit("recover_large_motion", o.recover_large_motion, Flag{});
  visit("max_step_error_px", o.max_step_error_px, Range<double>{0.0, 1000.0});
  visit("dragged_ratio", o.dragged_ratio, Range<double>{0.0, 1.0});
  visit("dragged_patch_radius_px", o.dragged_patch_radius_px, Range<int>{1, 8});
  visit("dragged_min_difference", o.dragged_min_difference, Range<double>{0.0, 255.0});
  visit("aperture_ratio", o.aperture_ratio, Range<double>{0.0, 1.0});
  visit("aperture_min_car_px", o.aperture_min_car_px, Range<double>{0.0, 100000.0});
  visit("robust_method", o.robust_method, Choices{{"ransac", "magsac"}});
  visit("ransac_threshold_px", o.ransac_threshold_px, Range<double>{0.1, 50.0});
  visit("ransac_max_iterations", o.ransac_max_iterations, Range<int>{10, 100000});
  visit("ransac_confidence", o.ransac_confidence, Range<double>{0.5, 0.999999});
  visit("min_inliers", o.min_inliers, Range<int>{4, 100000});
  visit("min_inlier_ratio", o.min_inlier_ratio, Range<double>{0.0, 1.0});
  visit("min_tracked_ratio", o.min_tracked_ratio, Range<double>{0.0, 1.0});
  visit("max_motion_fraction", o.max_motion_fraction, Range<double>{0.001, 2.0});
  visit("max_scale_change", o.max_scale_change, Range<double>{0.001, 0.9});
  visit("refine", o.refine, Flag{});
  visit("refine_loss", o.refine_loss, Choices{{"cauchy", "huber", "none"}});
  visit("refine_loss_scale_px", o.refine_loss_scale_px, Range<double>{1e-3, 100.0});
  visit("refine_max_iterations", o.refine_max_iterations, Range<int>{1, 1000});
  visit("refine_max_points", o.refine_max_points, Range<int>{8, 1000000});
  visit("refine_exclude_moving", o.refine_exclude_moving, Flag{});
  visit("background_flow_degree", o.background_flow_degree, Range<int>{0, 4});
  visit("history_frames", o.history_frames, Range<int>{2, 200});
  visit("min_track_frames", o.min_track_frames, Range<int>{2, 200});
  visit("position_sigma_px", o.position_sigma_px, Range<double>{1e-4, 10.0});
  visit("prior_weight", o.prior_weight, Range<double>{0.0, 1000.0});
  visit("moving_sigma_factor", o.moving_sigma_factor, Range<double>{0.0, 100.0});
  visit("min_moving_speed_px", o.min_moving_speed_px, Range<double>{0.0, 1000.0});
  visit("min_moving_speed_mps", o.min_moving_speed_mps, Range<double>{0.0, 1000.0});
  visit("flat_scene_speed_factor", o.flat_scene_speed_factor, Range<double>{0.0, 1.0});
  visit("creep_speed_factor", o.creep_speed_factor, Range<double>{0.01, 1.0});
  visit("creep_max_drop_px", o.creep_max_drop_px, Range<double>{0.0, 1000.0});
  visit("creep_neighbour_lengths", o.creep_neighbour_lengths, Range<double>{0.0, 100.0});
  visit("creep_neighbour_ratio", o.creep_neighbour_ratio, Range<double>{1.0, 1000.0});
  visit("creep_min_support", o.creep_min_support, Range<int>{1, 1000});
  visit("scene_noise_factor", o.scene_noise_factor, Range<double>{0.0, 100.0});
  visit("scene_noise_max_px", o.scene_noise_max_px, Range<double>{0.0, 1000.0});
  visit("confirm_frames", o.confirm_frames, Range<int>{1, 100});
  visit("strong_motion_factor", o.strong_motion_factor, Range<double>{0.0, 100.0});
  visit("strong_motion_max_view_frames", o.strong_motion_max_view_frames, Range<double>{0.0, 1e6});
  visit("release_ratio", o.release_ratio, Range<double>{0.0, 1.0});
  visit("parallax_rejection", o.parallax_rejection, Flag{});
  visit("parallax_both_sides", o.parallax_both_sides, Flag{});
  visit("parallax_min_support", o.parallax_min_support, Range<int>{2, 100000});
  visit("parallax_min_support_density", o.parallax_min_support_density, Range<double>{0.0, 1e6});
  visit("parallax_min_support_fraction", o.parallax_min_support_fraction, Range<double>{0.0, 1.0});
  visit("parallax_min_share", o.parallax_min_share, Range<double>{0.0, 1.0});
  visit("parallax_min_spread", o.parallax_min_spread, Range<double>{0.0, 1.0});
  visit("parallax_stable_frames", o.parallax_stable_frames, Range<int>{1, 1000});
  visit("parallax_startup_frames", o.parallax_startup_frames, Range<int>{0, 100000});
  visit("parallax_stable_angle_deg", o.parallax_stable_angle_deg, Range<double>{0.0, 90.0});
  visit("parallax_across_sigma", o.parallax_across_sigma, Range<double>{0.0, 100.0});
  visit("parallax_across_floor_px", o.parallax_across_floor_px, Range<double>{0.0, 100.0});
  visit("parallax_max_height_ratio", o.parallax_max_height_ratio, Range<double>{0.0, 0.9});
  visit("parallax_cap_factor", o.parallax_cap_factor, Range<double>{0.0, 1000.0});
  visit("parallax_ransac_iterations", o.parallax_ransac_iterations, Range<int>{1, 100000});
  visit("parallax_edge_radius_px", o.parallax_edge_radius_px, Range<double>{0.0, 1000.0});
  visit("parallax_edge_min_supporters", o.parallax_edge_min_supporters, Range<int>{1, 100000});
  visit("parallax_edge_speed_factor", o.parallax_edge_speed_factor, Range<double>{0.0, 100.0});
  visit("structure_patch_ratio", o.structure_patch_ratio, Range<double>{0.0, 100.0});
  visit("structure_patch_radius_px", o.structure_patch_radius_px, Range<int>{1, 8});
}

// Reads a `motion:` section; absent keys keep their defaults. Throws uavmot::InputError naming
// the file, line and key for unknown keys, wrong types and out-of-range values.
MotionOptions load_motion_options(const ConfigNode& node);

// Throws uavmot::InputError when options contradict each other (e.g. an even LK window).
void validate(const MotionOptions& options);

// The LK window that lk_window_px = 0 stands for in `scene`: the odd number nearest to
// 0.85 x the car's length in pixels, clamped to [7, 11] (docs/motion.md): 11 at 0.38 m/px and
// finer, 9 at 0.45 m/px, 7 at 0.6 m/px (8 px cars).
int automatic_lk_window_px(const SceneInfo& scene);

// `options` with every scene-dependent value resolved for `scene` (lk_window_px = 0); what a
// MotionEstimator runs with and reports as options().
MotionOptions resolved_for_scene(MotionOptions options, const SceneInfo& scene);

// The classifier's speed floor (px/frame) in a frame where the parallax fit found no 3-D
// structure: flat_scene_speed_factor x min_moving_speed_px, never below min_moving_speed_mps in
// `scene`. `options` as given, not resolved.
double flat_scene_min_speed_px(const MotionOptions& options, const SceneInfo& scene);

}  // namespace uavmot::motion
