#include "uavmot/motion/motion_options.hpp"

#include <gtest/gtest.h>

#include "uavmot/motion/motion_estimator.hpp"

namespace uavmot::motion {
namespace {

TEST(MotionOptions, DefaultsAreValid) { EXPECT_NO_THROW(validate(MotionOptions{})); }

TEST(MotionOptions, ReadsKeysAndKeepsDefaults) {
  const auto node = ConfigNode::load_string(
      "max_features: 500\nrobust_method: magsac\nrefine_loss: huber\nmin_moving_speed_px: 0.2\n", "m.yaml");
  const MotionOptions o = load_motion_options(node);
  EXPECT_EQ(o.max_features, 500);
  EXPECT_EQ(o.robust_method, "magsac");
  EXPECT_EQ(o.refine_loss, "huber");
  EXPECT_DOUBLE_EQ(o.min_moving_speed_px, 0.2);
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
  expect_error("pyramid_levels: 9\n", "pyramid_levels");
  expect_error("robust_method: lmeds\n", "robust_method");
  expect_error("min_track_frames: 20\nhistory_frames: 10\n", "min_track_frames");
  expect_error("ransac_threshold_px: nan\n", "ransac_threshold_px");
}

TEST(MotionOptions, EstimatorRejectsInconsistentOptions) {
  MotionOptions o;
  o.lk_window_px = 10;
  EXPECT_THROW(MotionEstimator{o}, InputError);
  o = MotionOptions{};
  o.min_inliers = 3;
  EXPECT_THROW(MotionEstimator{o}, InputError);
}

}  // namespace
}  // namespace uavmot::motion
