#include "uavmot/segmentation/feature_clustering.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>

namespace uavmot::segmentation {
namespace {

TrackedFeature feature(uint64_t id, double x, double y, double vx, double vy, bool moving = true) {
  TrackedFeature f;
  f.id = id;
  f.position = {x, y};
  f.velocity = {vx, vy};
  f.velocity_sigma = 0.02;
  f.moving = moving;
  return f;
}

// A car-sized group of 5 features around (x, y), all with velocity (vx, vy).
std::vector<TrackedFeature> group(uint64_t first_id, double x, double y, double vx, double vy) {
  return {feature(first_id, x - 4, y - 2, vx, vy), feature(first_id + 1, x + 4, y - 2, vx, vy),
          feature(first_id + 2, x - 4, y + 2, vx, vy), feature(first_id + 3, x + 4, y + 2, vx, vy),
          feature(first_id + 4, x, y, vx, vy)};
}

std::vector<TrackedFeature> concat(std::vector<TrackedFeature> a, const std::vector<TrackedFeature>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

SceneInfo scene_at(double gsd) {
  SceneInfo s;
  s.gsd_m = gsd;
  s.fps = 25.0;
  return s;
}

TEST(LinkThresholds, ConvertMetresAndSpeedsWithTheGsd) {
  ClusteringOptions o;
  o.link_distance_m = 3.0;
  o.link_speed_difference_mps = 2.5;
  const auto t = link_thresholds(o, scene_at(0.25));
  EXPECT_DOUBLE_EQ(t.distance_px, 12.0);
  EXPECT_DOUBLE_EQ(t.velocity_px_per_frame, 2.5 / (0.25 * 25.0));
  EXPECT_DOUBLE_EQ(link_thresholds(o, scene_at(0.5)).distance_px, 6.0);
}

TEST(FeatureClustering, TwoWellSeparatedGroupsGiveTwoClusters) {
  const auto features = concat(group(10, 50, 50, 1.0, 0.0), group(20, 150, 80, 1.0, 0.0));
  const auto clusters = cluster_moving_features(features, {}, scene_at(0.35), cv::Size(640, 480));
  ASSERT_EQ(clusters.size(), 2u);
  EXPECT_EQ(clusters[0].id, 1u);
  EXPECT_EQ(clusters[1].id, 2u);
  EXPECT_EQ(clusters[0].feature_ids, (std::vector<uint64_t>{10, 11, 12, 13, 14}));
  EXPECT_EQ(clusters[1].feature_ids, (std::vector<uint64_t>{20, 21, 22, 23, 24}));
  EXPECT_NEAR(clusters[1].box.cx, 150.0, 1e-9);
  EXPECT_NEAR(clusters[1].box.cy, 80.0, 1e-9);
  EXPECT_NEAR(clusters[1].velocity[0], 1.0, 1e-12);
}

TEST(FeatureClustering, SamePositionDifferentVelocityIsSplit) {
  const auto features = concat(group(1, 50, 50, 1.5, 0.0), group(100, 50, 51, -1.5, 0.0));
  const auto clusters = cluster_moving_features(features, {}, scene_at(0.35), cv::Size(640, 480));
  ASSERT_EQ(clusters.size(), 2u);
  EXPECT_EQ(clusters[0].feature_ids.front(), 1u);
  EXPECT_EQ(clusters[1].feature_ids.front(), 100u);
  EXPECT_GT(clusters[0].velocity[0], 0.0);
  EXPECT_LT(clusters[1].velocity[0], 0.0);
}

TEST(FeatureClustering, NoisyVelocitiesStayTogether) {
  auto features = concat(group(1, 50, 50, 1.5, 0.0), group(100, 50, 51, -1.5, 0.0));
  for (auto& f : features) f.velocity_sigma = 2.0;  // 3 sigma covers the 3 px/frame difference
  EXPECT_EQ(cluster_moving_features(features, {}, scene_at(0.35), cv::Size(640, 480)).size(), 1u);
}

TEST(FeatureClustering, ThresholdsScaleWithTheGsd) {
  // Groups 16 px apart centre to centre: their nearest features are 8 px apart.
  const auto features = concat(group(1, 50, 50, 1.0, 0.0), group(10, 66, 50, 1.0, 0.0));
  // 3 m = 8.57 px at 0.35 m/px: linked; 3 m = 6 px at 0.5 m/px: apart.
  EXPECT_EQ(cluster_moving_features(features, {}, scene_at(0.35), cv::Size(640, 480)).size(), 1u);
  EXPECT_EQ(cluster_moving_features(features, {}, scene_at(0.5), cv::Size(640, 480)).size(), 2u);
}

TEST(FeatureClustering, SingleLinkageChainsAlongAConvoy) {
  // Five features in a row, each 5 px from the next: one cluster 20 px long.
  std::vector<TrackedFeature> features;
  for (int i = 0; i < 5; ++i) features.push_back(feature(i + 1, 100 + 5 * i, 100, 1.0, 0.0));
  const auto clusters = cluster_moving_features(features, {}, scene_at(0.35), cv::Size(640, 480));
  ASSERT_EQ(clusters.size(), 1u);
  EXPECT_NEAR(clusters[0].box.length, 20.0, 1e-9);
  EXPECT_NEAR(clusters[0].box.cx, 110.0, 1e-9);
}

TEST(FeatureClustering, BoxFollowsTheMotionAndIsAtLeastAVehicle) {
  // Two features 4 px apart moving at 45 degrees: box along the motion, vehicle-sized.
  const std::vector<TrackedFeature> features = {feature(1, 100, 100, 1.0, 1.0), feature(2, 102, 102, 1.0, 1.0)};
  const SceneInfo scene = scene_at(0.3);
  const auto clusters = cluster_moving_features(features, {}, scene, cv::Size(640, 480));
  ASSERT_EQ(clusters.size(), 1u);
  const auto& box = clusters[0].box;
  EXPECT_NEAR(box.angle_deg, 45.0, 1e-9);
  EXPECT_NEAR(box.length, scene.metres_to_px(scene.vehicle_length_m), 1e-9);
  EXPECT_NEAR(box.width, scene.metres_to_px(scene.vehicle_width_m), 1e-9);
  EXPECT_NEAR(box.cx, 101.0, 1e-9);
  EXPECT_NEAR(box.cy, 101.0, 1e-9);
}

TEST(FeatureClustering, SkipsStationaryNonFiniteAndOutsideFeatures) {
  auto features = group(1, 50, 50, 1.0, 0.0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  features.push_back(feature(50, nan, 50, 1.0, 0.0));
  features.push_back(feature(51, 52, 50, nan, 0.0));
  features.push_back(feature(52, 700, 50, 1.0, 0.0));
  features.push_back(feature(53, 55, -3, 1.0, 0.0));
  features.push_back(feature(54, 51, 50, 1.0, 0.0, /*moving=*/false));
  ClusteringStats stats;
  const auto clusters = cluster_moving_features(features, {}, scene_at(0.35), cv::Size(640, 480), &stats);
  ASSERT_EQ(clusters.size(), 1u);
  EXPECT_EQ(clusters[0].feature_ids, (std::vector<uint64_t>{1, 2, 3, 4, 5}));
  EXPECT_EQ(stats.moving_features, 9u);
  EXPECT_EQ(stats.skipped_non_finite, 2u);
  EXPECT_EQ(stats.skipped_outside, 2u);
}

TEST(FeatureClustering, DropsClustersWithTooFewFeatures) {
  auto features = group(1, 50, 50, 1.0, 0.0);
  features.push_back(feature(99, 300, 300, 1.0, 0.0));  // lone feature
  ClusteringOptions options;
  options.min_features = 2;
  ClusteringStats stats;
  const auto clusters = cluster_moving_features(features, options, scene_at(0.35), cv::Size(640, 480), &stats);
  EXPECT_EQ(clusters.size(), 1u);
  EXPECT_EQ(stats.dropped_small_clusters, 1u);
  EXPECT_EQ(cluster_moving_features(features, {}, scene_at(0.35), cv::Size(640, 480)).size(), 2u);  // default 1
}

TEST(FeatureClustering, ResultDoesNotDependOnFeatureOrder) {
  auto features = concat(concat(group(30, 50, 50, 1.0, 0.0), group(10, 150, 80, 1.0, 0.0)), group(20, 300, 80, 0, 1));
  const auto a = cluster_moving_features(features, {}, scene_at(0.35), cv::Size(640, 480));
  std::reverse(features.begin(), features.end());
  const auto b = cluster_moving_features(features, {}, scene_at(0.35), cv::Size(640, 480));
  ASSERT_EQ(a.size(), 3u);
  ASSERT_EQ(b.size(), 3u);
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].id, b[i].id);
    EXPECT_EQ(a[i].feature_ids, b[i].feature_ids);
    EXPECT_EQ(a[i].box, b[i].box);
  }
  EXPECT_EQ(a[0].feature_ids.front(), 10u);  // ordered by smallest feature id
}

}  // namespace
}  // namespace uavmot::segmentation
