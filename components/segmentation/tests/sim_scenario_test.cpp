// Scenario tests on the simulator (label scenario): segmentation methods scored with the
// paper's Table I rules by uavmot::eval, the chain's own motion layer supplying the features.

#include <gtest/gtest.h>

#include <cstdio>

#include "sim_tables.hpp"

namespace uavmot::segmentation {
namespace {

SimTables run(const std::string& preset, int frames) {
  SimTablesRequest request;
  request.preset = preset;
  request.seed = 3;
  request.frames = frames;
  request.methods = {SegmentationMethod::Clustering, SegmentationMethod::Fusion};
  SimTables tables = run_sim_tables(request);
  std::printf("%s\n", format_tables(tables).c_str());
  return tables;
}

double feature_bound(const SimTables& t) {
  return static_cast<double>(t.instances_with_moving_feature) / static_cast<double>(t.moving_instances);
}

TEST(SegmentationScenario, FusionBeatsClusteringOnPaper) {
  const SimTables t = run("paper", 80);
  const auto& clustering = t.results.at(SegmentationMethod::Clustering).completeness;
  const auto& fusion = t.results.at(SegmentationMethod::Fusion).completeness;
  ASSERT_GT(fusion.instances, 1000);
  EXPECT_GT(fusion.correct_rate(), clustering.correct_rate() + 0.15);
  EXPECT_LE(fusion.rate(fusion.under_segmented), clustering.rate(clustering.under_segmented));
  // Segmentation starts from moving features: most objects that carry one are found correctly.
  EXPECT_GT(fusion.correct_rate(), 0.8 * feature_bound(t));
  const auto& precision = t.results.at(SegmentationMethod::Fusion).precision;
  EXPECT_LT(precision.error_x_px, 1.5);
  EXPECT_LT(precision.error_y_px, 1.5);
}

TEST(SegmentationScenario, FusionBeatsClusteringOnDense) {
  const SimTables t = run("dense", 60);
  const auto& clustering = t.results.at(SegmentationMethod::Clustering).completeness;
  const auto& fusion = t.results.at(SegmentationMethod::Fusion).completeness;
  ASSERT_GT(fusion.instances, 1000);
  EXPECT_GT(fusion.correct_rate(), clustering.correct_rate() + 0.1);
  EXPECT_LE(fusion.rate(fusion.under_segmented), clustering.rate(clustering.under_segmented));
}

}  // namespace
}  // namespace uavmot::segmentation
