#include <gtest/gtest.h>

#include "uavmot/core/error.hpp"
#include "uavmot/tracking/tracker.hpp"

namespace uavmot::tracking {
namespace {

TEST(TrackerOptions, DefaultsFollowThePaper) {
  const TrackerOptions o;
  EXPECT_EQ(o.max_features_per_track, 20);  // paper IV-B
  EXPECT_LT(o.min_intersection_fraction, 0.2);  // "chosen small"
  EXPECT_GT(o.max_coast_frames, 0);          // "kept alive for a few time steps"
  EXPECT_NO_THROW(validate(o));
}

TEST(TrackerOptions, LoadsAndValidatesYaml) {
  const auto node = ConfigNode::load_string("max_features_per_track: 12\nmax_coast_frames: 8\nregion_method: all\n", "t.yaml");
  const TrackerOptions o = load_tracker_options(node);
  EXPECT_EQ(o.max_features_per_track, 12);
  EXPECT_EQ(o.max_coast_frames, 8);
  EXPECT_EQ(o.region_method, "all");
  EXPECT_EQ(o.confirm_hits, TrackerOptions{}.confirm_hits);
  const TrackerOptions entering =
      load_tracker_options(ConfigNode::load_string("confirm_entering_max_angle_deg: 0\nconfirm_entering_min_features: 2\n", "t.yaml"));
  EXPECT_EQ(entering.confirm_entering_max_angle_deg, 0.0);  // the rule off
  EXPECT_EQ(entering.confirm_entering_min_features, 2);
  EXPECT_EQ(o.confirm_entering_max_angle_deg, 60.0);
}

TEST(TrackerOptions, RejectsBadValuesNamingTheKey) {
  auto expect_error = [](const std::string& yaml, const std::string& key) {
    try {
      load_tracker_options(ConfigNode::load_string(yaml, "t.yaml"));
      ADD_FAILURE() << "accepted: " << yaml;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
    }
  };
  expect_error("max_features_per_track: -3\n", "max_features_per_track");
  expect_error("min_intersection_fraction: 2.0\n", "min_intersection_fraction");
  expect_error("region_method: magic\n", "region_method");
  expect_error("motion_model: magic\n", "motion_model");
  expect_error("max_coast_frame: 3\n", "max_coast_frame");  // typo
  expect_error("process_accel_sigma_px: fast\n", "process_accel_sigma_px");
  expect_error("confirm_hits: 6\nconfirm_window: 4\n", "confirm_hits");
  expect_error("confirm_entering_max_angle_deg: 95\n", "confirm_entering_max_angle_deg");
  expect_error("confirm_entering_max_angle_deg: .nan\n", "confirm_entering_max_angle_deg");
  expect_error("confirm_entering_min_features: -1\n", "confirm_entering_min_features");
}

TEST(TrackerOptions, TrackerRejectsInvalidOptions) {
  TrackerOptions o;
  o.region_size_sigma_px = -1.0;
  EXPECT_THROW(Tracker{o}, InvalidArgument);
  o = TrackerOptions{};
  o.reconstruction_sigma_px = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(Tracker{o}, InvalidArgument);
}

}  // namespace
}  // namespace uavmot::tracking

namespace uavmot::tracking {
namespace {

TEST(TrackOutput, SpeedInMetresAndKilometresPerHour) {
  Track t;
  t.velocity = cv::Vec2d(3.0, 4.0);  // 5 px/frame
  SceneInfo scene;
  scene.gsd_m = 0.2;
  scene.fps = 25.0;
  EXPECT_DOUBLE_EQ(speed_mps(t, scene), 25.0);  // 5 px x 0.2 m x 25 /s
  EXPECT_DOUBLE_EQ(speed_kmh(t, scene), 90.0);
}

}  // namespace
}  // namespace uavmot::tracking
