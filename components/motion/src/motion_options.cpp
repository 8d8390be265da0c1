#include "uavmot/motion/motion_options.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace uavmot::motion {
namespace {

void read_option(const ConfigNode& node, const char* key, bool& value, Flag) { node.read(key, value); }
void read_option(const ConfigNode& node, const char* key, std::string& value, const Choices& choices) {
  node.read_choice(key, value, std::vector<std::string>(choices.names.begin(), choices.names.end()));
}
template <class T>
void read_option(const ConfigNode& node, const char* key, T& value, const Range<T>& range) {
  node.read(key, value, range.low, range.high);
}

}  // namespace

MotionOptions load_motion_options(const ConfigNode& node) {
  MotionOptions o;
  std::vector<std::string> keys;
  for_each_motion_option(o, [&](const char* key, auto&, const auto&) { keys.emplace_back(key); });
  node.expect_only(keys);
  for_each_motion_option(o, [&](const char* key, auto& value, const auto& limits) { read_option(node, key, value, limits); });
  if (o.cell_size_px > 0 && o.cell_size_px < 8) node.fail("cell_size_px", "must be 0 (automatic) or >= 8");
  if (o.lk_window_px != 0 && (o.lk_window_px < 5 || o.lk_window_px % 2 == 0)) {
    node.fail("lk_window_px", "must be 0 (automatic) or odd and >= 5, got " + std::to_string(o.lk_window_px));
  }
  if (o.corner_block_size % 2 == 0) {
    node.fail("corner_block_size", "must be odd, got " + std::to_string(o.corner_block_size));
  }
  if (o.min_track_frames > o.history_frames) {
    node.fail("min_track_frames", "must not exceed history_frames (" + std::to_string(o.history_frames) + ")");
  }
  if (o.backward_levels > o.pyramid_levels) {
    node.fail("backward_levels", "must not exceed pyramid_levels (" + std::to_string(o.pyramid_levels) + ")");
  }
  if (o.lk_quick_levels > o.pyramid_levels) {
    node.fail("lk_quick_levels", "must not exceed pyramid_levels (" + std::to_string(o.pyramid_levels) +
                                     "); its default is 2, so with fewer pyramid levels set it too");
  }
  return o;
}

namespace {
void require(bool ok, const std::string& message) {
  if (!ok) throw InputError("motion options: " + message);
}
}  // namespace

void validate(const MotionOptions& o) {
  require(o.max_features >= 10, "max_features must be >= 10");
  require(o.cell_size_px == 0 || o.cell_size_px >= 8, "cell_size_px must be 0 (automatic) or >= 8");
  require(o.features_per_cell >= 1, "features_per_cell must be >= 1");
  require(o.min_distance_px >= 1.0, "min_distance_px must be >= 1");
  require(o.corner_block_size >= 3 && o.corner_block_size % 2 == 1, "corner_block_size must be odd and >= 3");
  require(o.min_corner_response >= 0.0, "min_corner_response must be >= 0");
  require(o.border_px >= 0, "border_px must be >= 0");
  require(o.blank_band_max_grey >= 0.0 && o.blank_band_max_grey <= 63.0, "blank_band_max_grey must be in [0, 63]");
  require(o.empty_cell_retry_frames >= 1, "empty_cell_retry_frames must be >= 1");
  require(o.empty_cell_retry_shift_cells >= 0.0, "empty_cell_retry_shift_cells must be >= 0");
  require(o.sparse_features_fraction >= 0.0 && o.sparse_features_fraction <= 1.0, "sparse_features_fraction must be in [0, 1]");
  require(o.sparse_response_factor >= 0.0 && o.sparse_response_factor <= 1.0, "sparse_response_factor must be in [0, 1]");
  require(o.lk_window_px == 0 || (o.lk_window_px >= 5 && o.lk_window_px % 2 == 1),
          "lk_window_px must be 0 (automatic) or odd and >= 5");
  require(o.pyramid_levels >= 0 && o.pyramid_levels <= 6, "pyramid_levels must be in [0, 6]");
  require(o.backward_levels >= 0 && o.backward_levels <= o.pyramid_levels,
          "backward_levels must be in [0, pyramid_levels]");
  require(o.lk_quick_levels >= 0 && o.lk_quick_levels <= o.pyramid_levels,
          "lk_quick_levels must be in [0, pyramid_levels]");
  require(o.lk_max_iterations >= 1 && o.lk_epsilon_px > 0.0, "LK stopping criteria must be positive");
  require(o.max_forward_backward_px > 0.0, "max_forward_backward_px must be > 0");
  require(o.max_step_error_px >= 0.0, "max_step_error_px must be >= 0 (0 turns the slip check off)");
  require(o.robust_method == "ransac" || o.robust_method == "magsac", "robust_method must be ransac or magsac");
  require(o.ransac_threshold_px > 0.0, "ransac_threshold_px must be > 0");
  require(o.ransac_max_iterations >= 10, "ransac_max_iterations must be >= 10");
  require(o.ransac_confidence > 0.0 && o.ransac_confidence < 1.0, "ransac_confidence must be in (0, 1)");
  require(o.min_inliers >= 4, "min_inliers must be >= 4 (a homography needs 4 points)");
  require(o.min_inlier_ratio >= 0.0 && o.min_inlier_ratio <= 1.0, "min_inlier_ratio must be in [0, 1]");
  require(o.min_tracked_ratio >= 0.0 && o.min_tracked_ratio <= 1.0, "min_tracked_ratio must be in [0, 1]");
  require(o.max_motion_fraction > 0.0, "max_motion_fraction must be > 0");
  require(o.max_scale_change > 0.0 && o.max_scale_change < 1.0, "max_scale_change must be in (0, 1)");
  require(o.refine_loss == "cauchy" || o.refine_loss == "huber" || o.refine_loss == "none",
          "refine_loss must be cauchy, huber or none");
  require(o.refine_loss_scale_px > 0.0, "refine_loss_scale_px must be > 0");
  require(o.refine_max_iterations >= 1, "refine_max_iterations must be >= 1");
  require(o.refine_max_points >= 8, "refine_max_points must be >= 8 (4 points fix a homography; more average the noise)");
  require(o.background_flow_degree >= 0 && o.background_flow_degree <= 4, "background_flow_degree must be in [0, 4]");
  require(o.history_frames >= 2, "history_frames must be >= 2");
  require(o.min_track_frames >= 2 && o.min_track_frames <= o.history_frames,
          "min_track_frames must be in [2, history_frames]");
  require(o.position_sigma_px > 0.0, "position_sigma_px must be > 0");
  require(o.prior_weight >= 0.0, "prior_weight must be >= 0");
  require(o.moving_sigma_factor >= 0.0 && o.min_moving_speed_px >= 0.0 && o.min_moving_speed_mps >= 0.0 &&
              o.scene_noise_factor >= 0.0 && o.scene_noise_max_px >= 0.0,
          "moving thresholds must be >= 0");
  require(o.confirm_frames >= 1, "confirm_frames must be >= 1");
  require(o.aperture_ratio >= 0.0 && o.aperture_ratio <= 1.0, "aperture_ratio must be in [0, 1] (0 = off)");
  require(o.aperture_min_car_px >= 0.0, "aperture_min_car_px must be >= 0");
  require(o.release_ratio >= 0.0 && o.release_ratio <= 1.0, "release_ratio must be in [0, 1]");
  require(o.creep_speed_factor > 0.0 && o.creep_speed_factor <= 1.0, "creep_speed_factor must be in (0, 1] (1 = off)");
  require(o.creep_max_drop_px >= 0.0, "creep_max_drop_px must be >= 0");
  require(o.creep_neighbour_lengths >= 0.0, "creep_neighbour_lengths must be >= 0");
  require(o.creep_neighbour_ratio >= 1.0, "creep_neighbour_ratio must be >= 1");
  require(o.creep_min_support >= 1, "creep_min_support must be >= 1");
  require(o.strong_motion_factor == 0.0 || o.strong_motion_factor >= 1.0,
          "strong_motion_factor must be 0 (off) or >= 1 (a multiple of the moving threshold)");
  require(o.strong_motion_max_view_frames >= 0.0, "strong_motion_max_view_frames must be >= 0 (0 = always)");
  require(o.parallax_min_support >= 2, "parallax_min_support must be >= 2 (two lines fix an epipole)");
  require(o.parallax_min_support_fraction >= 0.0 && o.parallax_min_support_fraction <= 1.0,
          "parallax_min_support_fraction must be in [0, 1]");
  require(o.parallax_min_spread >= 0.0 && o.parallax_min_spread <= 1.0, "parallax_min_spread must be in [0, 1]");
  require(o.parallax_min_share >= 0.0 && o.parallax_min_share <= 1.0, "parallax_min_share must be in [0, 1]");
  require(o.parallax_stable_frames >= 1, "parallax_stable_frames must be >= 1");
  require(o.parallax_stable_angle_deg >= 0.0 && o.parallax_stable_angle_deg <= 90.0, "parallax_stable_angle_deg must be in [0, 90]");
  require(o.parallax_across_sigma >= 0.0 && o.parallax_across_floor_px >= 0.0 && o.parallax_cap_factor >= 0.0,
          "parallax tolerances must be >= 0");
  require(o.parallax_max_height_ratio >= 0.0 && o.parallax_max_height_ratio < 1.0,
          "parallax_max_height_ratio (tallest structure / flight height) must be in [0, 1)");
  require(o.parallax_ransac_iterations >= 1, "parallax_ransac_iterations must be >= 1");
  require(o.parallax_edge_radius_px >= 0.0 && o.parallax_edge_speed_factor >= 0.0,
          "parallax_edge_radius_px and parallax_edge_speed_factor must be >= 0");
  require(o.parallax_edge_min_supporters >= 1, "parallax_edge_min_supporters must be >= 1");
}

int automatic_lk_window_px(const SceneInfo& scene) {
  if (!(scene.gsd_m > 0.0) || !(scene.vehicle_length_m > 0.0)) {
    throw InputError("motion options: lk_window_px 0 (automatic) needs a scene with gsd_m > 0 and vehicle_length_m > 0");
  }
  // 0.85 keeps 11 down to 12 px cars (0.38 m/px): at 0.35 m/px a 9 px window gained 0.3-1 point
  // in the simulator but lost the real 1-fps car of aphill (docs/motion.md); at 0.6 m/px (8 px
  // cars) 7 beats 11 by 4-5 points.
  const double target = 0.85 * scene.metres_to_px(scene.vehicle_length_m);
  const double odd = 2.0 * std::round((target - 1.0) / 2.0) + 1.0;
  return static_cast<int>(std::clamp(odd, 7.0, 11.0));
}

namespace {

// min_moving_speed_mps in px/frame in `scene` (0 when unused).
double ground_speed_floor_px(const MotionOptions& o, const SceneInfo& scene) {
  if (!(o.min_moving_speed_mps > 0.0)) return 0.0;
  if (!(scene.gsd_m > 0.0) || !(scene.fps > 0.0)) {
    throw InputError("motion options: min_moving_speed_mps needs a scene with gsd_m > 0 and fps > 0");
  }
  return o.min_moving_speed_mps / (scene.gsd_m * scene.fps);
}

}  // namespace

MotionOptions resolved_for_scene(MotionOptions o, const SceneInfo& scene) {
  validate(o);
  if (o.lk_window_px == 0) o.lk_window_px = automatic_lk_window_px(scene);
  // One threshold in px/frame for the classifier: the stricter of the two.
  o.min_moving_speed_px = std::max(o.min_moving_speed_px, ground_speed_floor_px(o, scene));
  return o;
}

double flat_scene_min_speed_px(const MotionOptions& o, const SceneInfo& scene) {
  validate(o);
  return std::max(o.flat_scene_speed_factor * o.min_moving_speed_px, ground_speed_floor_px(o, scene));
}

}  // namespace uavmot::motion
