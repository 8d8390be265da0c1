#include "uavmot/motion/motion_options.hpp"

#include <cstdio>
#include <limits>
#include <string>
#include <type_traits>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "grid_corner_detector.hpp"
#include "uavmot/core/error.hpp"
#include "uavmot/motion/motion_estimator.hpp"

namespace uavmot::motion {
namespace {

TEST(MotionOptions, DefaultsAreValid) { EXPECT_NO_THROW(validate(MotionOptions{})); }

TEST(MotionOptions, ReadsKeysAndKeepsDefaults) {
  const auto node = ConfigNode::load_string(
      "max_features: 500\nrobust_method: magsac\nrefine_loss: huber\nmin_moving_speed_px: 0.2\nmin_moving_speed_mps: 1.5\n",
      "m.yaml");
  const MotionOptions o = load_motion_options(node);
  EXPECT_EQ(o.max_features, 500);
  EXPECT_EQ(o.robust_method, "magsac");
  EXPECT_EQ(o.refine_loss, "huber");
  EXPECT_DOUBLE_EQ(o.min_moving_speed_px, 0.2);
  EXPECT_DOUBLE_EQ(o.min_moving_speed_mps, 1.5);
  EXPECT_EQ(o.lk_window_px, MotionOptions{}.lk_window_px);
}

void expect_error(const std::string& yaml, const std::string& fragment) {
  try {
    load_motion_options(ConfigNode::load_string(yaml, "m.yaml"));
    FAIL() << "expected InputError for " << yaml;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("m.yaml"), std::string::npos) << e.what();
  }
}

TEST(MotionOptions, RejectsBadValuesNamingTheKey) {
  expect_error("max_featurs: 5\n", "max_features");
  expect_error("lk_window_px: 12\n", "lk_window_px");
  expect_error("lk_window_px: 3\n", "lk_window_px");
  expect_error("pyramid_levels: 9\n", "pyramid_levels");
  expect_error("pyramid_levels: 1\nlk_quick_levels: 2\n", "lk_quick_levels");
  expect_error("robust_method: lmeds\n", "robust_method");
  expect_error("min_track_frames: 20\nhistory_frames: 10\n", "min_track_frames");
  expect_error("ransac_threshold_px: nan\n", "ransac_threshold_px");
  expect_error("parallax_edge_radius_px: -1\n", "parallax_edge_radius_px");
  expect_error("parallax_edge_min_supporters: 0\n", "parallax_edge_min_supporters");
  expect_error("parallax_edge_speed_factor: -0.5\n", "parallax_edge_speed_factor");
  expect_error("structure_patch_ratio: -1\n", "structure_patch_ratio");
  expect_error("structure_patch_ratio: .nan\n", "structure_patch_ratio");
  expect_error("structure_patch_radius_px: 0\n", "structure_patch_radius_px");
  expect_error("structure_patch_radius_px: 9\n", "structure_patch_radius_px");
}

// The options' keys, in the order of for_each_motion_option.
std::vector<std::string> option_keys() {
  std::vector<std::string> keys;
  const MotionOptions o;
  for_each_motion_option(o, [&](const char* key, const auto&, const auto&) { keys.emplace_back(key); });
  return keys;
}

std::string yaml_value(bool v) { return v ? "true" : "false"; }
std::string yaml_value(const std::string& v) { return v; }
std::string yaml_value(int v) { return std::to_string(v); }
std::string yaml_value(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

// Every option as "key: value" lines, doubles exactly.
std::string printed(const MotionOptions& o) {
  std::string out;
  for_each_motion_option(o, [&](const char* key, const auto& value, const auto&) { out += std::string(key) + ": " + yaml_value(value) + "\n"; });
  return out;
}

bool valid(const MotionOptions& o) {
  try {
    validate(o);
    return true;
  } catch (const InputError&) {
    return false;
  }
}

// The defaults with option INDEX (of for_each_motion_option) set to another value within its
// limits that keeps the options valid; its YAML text in `text`.
MotionOptions with_option_changed(size_t index, std::string& text) {
  MotionOptions changed;
  size_t at = 0;
  bool done = false;
  for_each_motion_option(changed, [&](const char*, auto& value, const auto& limits) {
    if (at++ != index) return;
    using T = std::decay_t<decltype(value)>;
    const T original = value;
    std::vector<T> candidates;
    if constexpr (std::is_same_v<T, bool>) {
      candidates = {!original};
    } else if constexpr (std::is_same_v<T, std::string>) {
      for (const char* name : limits.names) candidates.emplace_back(name);
    } else if constexpr (std::is_same_v<T, int>) {
      candidates = {original + 2, original - 2, original + 1, original - 1, limits.low, limits.high};
    } else {
      candidates = {original * 1.5, original * 0.5, (limits.low + limits.high) / 2, limits.low, limits.high};
    }
    for (const T& candidate : candidates) {
      if constexpr (!std::is_same_v<T, bool> && !std::is_same_v<T, std::string>) {
        if (candidate < limits.low || candidate > limits.high) continue;
      }
      if (candidate == original) continue;
      value = candidate;
      if (valid(changed)) {
        text = yaml_value(candidate);
        done = true;
        return;
      }
    }
    value = original;
  });
  EXPECT_TRUE(done) << "no other valid value for option " << index;
  return changed;
}

TEST(MotionOptions, EveryOptionIsReadFromTheConfigurationFile) {
  const std::vector<std::string> keys = option_keys();
  ASSERT_GE(keys.size(), 56u);
  for (size_t i = 0; i < keys.size(); ++i) {
    std::string text;
    const MotionOptions changed = with_option_changed(i, text);
    const std::string yaml = keys[i] + ": " + text + "\n";
    EXPECT_EQ(printed(load_motion_options(ConfigNode::load_string(yaml, "m.yaml"))), printed(changed)) << yaml;
    EXPECT_NE(printed(changed), printed(MotionOptions{})) << yaml;
  }
}

// The saved state's options fingerprint covers every option: a state saved under the defaults is
// refused by an estimator with any one option changed (and restored by one with the defaults).
TEST(MotionOptions, ChangingAnyOptionRefusesASavedState) {
  const std::vector<uint8_t> state = MotionEstimator(MotionOptions{}).save_state();
  MotionEstimator same(MotionOptions{});
  EXPECT_NO_THROW(same.restore_state(state));
  const std::vector<std::string> keys = option_keys();
  for (size_t i = 0; i < keys.size(); ++i) {
    std::string text;
    MotionEstimator other(with_option_changed(i, text));
    try {
      other.restore_state(state);
      ADD_FAILURE() << "a state saved with the default " << keys[i] << " was restored with " << keys[i] << " = " << text;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("saved with other motion options"), std::string::npos) << keys[i] << ": " << e.what();
    }
  }
}

SceneInfo scene_at(double gsd_m) {
  SceneInfo scene;
  scene.gsd_m = gsd_m;
  return scene;
}

// lk_window_px 0: about 0.85 of a 4.5 m car in pixels, odd, within [7, 11].
TEST(MotionOptions, AutomaticLkWindowFollowsTheCarsSizeInPixels) {
  EXPECT_EQ(MotionOptions{}.lk_window_px, 0);
  EXPECT_EQ(automatic_lk_window_px(scene_at(0.6)), 7);    // `small`: 7.5 px cars
  EXPECT_EQ(automatic_lk_window_px(scene_at(0.45)), 9);   // 10 px
  EXPECT_EQ(automatic_lk_window_px(scene_at(0.35)), 11);  // `paper` and the default scene: 12.9 px
  EXPECT_EQ(automatic_lk_window_px(scene_at(0.3)), 11);   // `hd`: 15 px
  EXPECT_EQ(automatic_lk_window_px(scene_at(0.05)), 11);  // FMV at low altitude: 90 px, capped
  EXPECT_EQ(automatic_lk_window_px(scene_at(5.0)), 7);    // sub-pixel cars: the floor
  EXPECT_THROW(automatic_lk_window_px(scene_at(0.0)), InputError);

  // The estimator runs with, and reports, the resolved window; an explicit one is kept.
  EXPECT_EQ(MotionEstimator(MotionOptions{}, scene_at(0.6)).options().lk_window_px, 7);
  MotionOptions fixed;
  fixed.lk_window_px = 13;
  EXPECT_EQ(MotionEstimator(fixed, scene_at(0.6)).options().lk_window_px, 13);
  EXPECT_EQ(load_motion_options(ConfigNode::load_string("lk_window_px: 0\n", "m.yaml")).lk_window_px, 0);
}

TEST(MotionOptions, FlatSceneFloorLowersThePixelFloorOnlyDownToTheGroundSpeed) {
  MotionOptions o;  // 0.15 px/frame, 1 m/s, factor 0.8
  EXPECT_DOUBLE_EQ(o.flat_scene_speed_factor, 0.8);
  // `small` (0.6 m/px at 25 fps: 1 m/s is 0.067 px/frame) and `paper` (0.35 m/px: 0.114): the
  // scaled pixel floor, 0.12, governs.
  EXPECT_NEAR(flat_scene_min_speed_px(o, scene_at(0.6)), 0.12, 1e-9);
  EXPECT_NEAR(flat_scene_min_speed_px(o, scene_at(0.35)), 0.12, 1e-9);
  // `hd`, 0.3 m/px: 1 m/s is 0.133 px/frame, above 0.12.
  EXPECT_NEAR(flat_scene_min_speed_px(o, scene_at(0.3)), 1.0 / (0.3 * 25.0), 1e-9);
  // FMV at 0.05 m/px: the ground-speed floor (0.8 px/frame) is all there is, with structure or not.
  EXPECT_NEAR(flat_scene_min_speed_px(o, scene_at(0.05)), resolved_for_scene(o, scene_at(0.05)).min_moving_speed_px, 1e-12);
  // Off: the same floor as in frames with structure.
  o.flat_scene_speed_factor = 1.0;
  EXPECT_DOUBLE_EQ(flat_scene_min_speed_px(o, scene_at(0.6)), resolved_for_scene(o, scene_at(0.6)).min_moving_speed_px);
  EXPECT_THROW(load_motion_options(ConfigNode::load_string("flat_scene_speed_factor: 1.5\n", "m.yaml")), InputError);
}

TEST(MotionOptions, TheCreepRuleRefusesFactorsOutsideItsRange) {
  EXPECT_NO_THROW(load_motion_options(ConfigNode::load_string("creep_speed_factor: 0.6\n", "m.yaml")));
  for (const char* bad : {"creep_speed_factor: 0\n", "creep_speed_factor: 1.2\n", "creep_speed_factor: .nan\n",
                          "creep_neighbour_ratio: 0.5\n", "creep_neighbour_lengths: -1\n", "creep_min_support: 0\n",
                          "creep_max_drop_px: -0.1\n"}) {
    EXPECT_THROW(load_motion_options(ConfigNode::load_string(bad, "m.yaml")), InputError) << bad;
  }
}

TEST(MotionOptions, EstimatorRejectsInconsistentOptions) {
  MotionOptions o;
  o.lk_window_px = 10;
  EXPECT_THROW(MotionEstimator{o}, InputError);
  o = MotionOptions{};
  o.min_inliers = 3;
  EXPECT_THROW(MotionEstimator{o}, InputError);
  // Set in code, not read from YAML: a NaN would otherwise turn the check off without a word.
  o = MotionOptions{};
  o.aperture_ratio = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(MotionEstimator{o}, InputError);
  o = MotionOptions{};
  o.blank_band_max_grey = -1.0;
  EXPECT_THROW(MotionEstimator{o}, InputError);
}

TEST(MotionOptions, GroundSpeedThresholdUsesTheScene) {
  MotionOptions o;
  o.min_moving_speed_px = 0.15;
  o.min_moving_speed_mps = 3.5;  // 3.5 m/s at 0.35 m/px and 25 fps = 0.4 px/frame
  SceneInfo scene;
  scene.gsd_m = 0.35;
  scene.fps = 25.0;
  EXPECT_NEAR(MotionEstimator(o, scene).options().min_moving_speed_px, 0.4, 1e-12);
  o.min_moving_speed_mps = 0.35;  // 0.04 px/frame: the px threshold is stricter
  EXPECT_DOUBLE_EQ(MotionEstimator(o, scene).options().min_moving_speed_px, 0.15);
}

TEST(MotionOptions, AutomaticCellSizeHoldsMaxFeatures) {
  MotionOptions o;
  o.cell_size_px = 0;
  o.max_features = 1000;
  EXPECT_EQ(detection_cell_size(o, {1920, 1080}), 46);  // sqrt(1920 * 1080 / 1000) = 45.5
  EXPECT_EQ(detection_cell_size(o, {800, 600}), 22);
  o.cell_size_px = 48;
  EXPECT_EQ(detection_cell_size(o, {800, 600}), 48);
  EXPECT_EQ(load_motion_options(ConfigNode::load_string("cell_size_px: 0\n", "m.yaml")).cell_size_px, 0);
  EXPECT_THROW(load_motion_options(ConfigNode::load_string("cell_size_px: 5\n", "m.yaml")), InputError);
}

TEST(GridCornerDetector, RespectsCellsDistanceAndCap) {
  cv::Mat image(240, 320, CV_8UC1, cv::Scalar(60));
  cv::RNG rng(5);
  for (int i = 0; i < 300; ++i) {
    image(cv::Rect(rng.uniform(0, 310), rng.uniform(0, 230), 6, 6)).setTo(rng.uniform(150, 255));
  }
  MotionOptions o;
  o.cell_size_px = 40;
  const auto corners = detect_missing_corners(image, {}, o);
  ASSERT_GT(corners.size(), 20u);
  EXPECT_LE(corners.size(), static_cast<size_t>((320 / 40) * (240 / 40)));
  for (size_t i = 0; i < corners.size(); ++i) {
    EXPECT_GE(corners[i].x, o.border_px);
    EXPECT_GE(corners[i].y, o.border_px);
    for (size_t j = i + 1; j < corners.size(); ++j) EXPECT_GE(cv::norm(corners[i] - corners[j]), o.min_distance_px);
  }
  // Cells that already hold a feature get none.
  const auto again = detect_missing_corners(image, corners, o);
  EXPECT_TRUE(again.empty());
  o.max_features = 10;
  EXPECT_EQ(detect_missing_corners(image, {}, o).size(), 10u);
  // A flat, noisy image gives no corners at the default response threshold.
  cv::Mat noise(240, 320, CV_16SC1);
  rng.fill(noise, cv::RNG::NORMAL, 128, 2);
  cv::Mat flat;
  noise.convertTo(flat, CV_8UC1);
  EXPECT_TRUE(detect_missing_corners(flat, {}, MotionOptions{}).empty());
}

}  // namespace
}  // namespace uavmot::motion
