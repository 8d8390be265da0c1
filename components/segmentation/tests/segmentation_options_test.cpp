#include "uavmot/segmentation/segmentation_options.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "uavmot/core/error.hpp"

namespace uavmot::segmentation {
namespace {

SegmentationOptions load(const std::string& yaml) {
  return load_segmentation_options(ConfigNode::load_string(yaml, "test.yaml"));
}

void expect_error_mentions(const std::string& yaml, const std::string& needle) {
  try {
    load(yaml);
    FAIL() << "no error for: " << yaml;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
  }
}

TEST(SegmentationOptions, DefaultsAreValidAndFusion) {
  const SegmentationOptions o = load("{}");
  EXPECT_EQ(o.method, SegmentationMethod::Fusion);
  EXPECT_NO_THROW(validate(o));
}

TEST(SegmentationOptions, AcceptsEveryListedMethodByName) {
  for (SegmentationMethod method : kSegmentationMethods) {
    EXPECT_EQ(load(std::string("method: ") + to_string(method) + "\n").method, method);
  }
  expect_error_mentions("method: sobol\n", "fusion");
}

TEST(SegmentationOptions, ReadsEveryKindOfField) {
  const SegmentationOptions o = load(
      "method: lbp\nlink_distance_m: 4.5\nkorn_sigmas_px: [1.0, 2.0]\nmorphological_sizes_px: [3, 7]\n"
      "lbp_radii_px: [1, 3]\nfusion_rule: product\nfallback_to_cluster_box: false\nmin_features: 3\n");
  EXPECT_EQ(o.method, SegmentationMethod::Lbp);
  EXPECT_DOUBLE_EQ(o.clustering.link_distance_m, 4.5);
  EXPECT_EQ(o.gradients.korn_sigmas_px, (std::vector<double>{1.0, 2.0}));
  EXPECT_EQ(o.gradients.morphological_sizes_px, (std::vector<int>{3, 7}));
  EXPECT_EQ(o.gradients.lbp_radii_px, (std::vector<double>{1.0, 3.0}));
  EXPECT_EQ(o.regions.fusion_rule, FusionRule::Product);
  EXPECT_FALSE(o.regions.fallback_to_cluster_box);
  EXPECT_EQ(o.clustering.min_features, 3);
}

TEST(SegmentationOptions, BadValuesNameTheField) {
  expect_error_mentions("method: watershed\n", "method");
  expect_error_mentions("link_distanse_m: 3\n", "link_distanse_m");
  expect_error_mentions("morphological_sizes_px: [3, 4]\n", "morphological_sizes_px");
  expect_error_mentions("korn_sigmas_px: []\n", "korn_sigmas_px");
  expect_error_mentions("korn_sigmas_px: [1, abc]\n", "korn_sigmas_px");
  expect_error_mentions("threshold_quantile: 1.5\n", "threshold_quantile");
  expect_error_mentions("closing_size_px: 4\n", "closing_size_px");
  expect_error_mentions("min_length_factor: 2\nmax_length_factor: 1\n", "max_length_factor");
  expect_error_mentions("shadow_correction_factor: -1\n", "shadow_correction_factor");
  expect_error_mentions("shadow_size_correction_factor: 3\n", "shadow_size_correction_factor");
  expect_error_mentions("shadow_size_correction_factor: .nan\n", "shadow_size_correction_factor");
  expect_error_mentions("shadow_min_regions: 0\n", "shadow_min_regions");
  expect_error_mentions("shadow_max_m: .nan\n", "shadow_max_m");
}

TEST(SegmentationOptions, ReadsTheShadowCorrection) {
  const SegmentationOptions o = load(
      "shadow_correction_factor: 0.5\nshadow_max_m: 3\nshadow_bright_margin: 20\nshadow_min_regions: 4\n"
      "shadow_agreement_px: 0.5\nshadow_min_darkness: 5\nshadow_size_correction_factor: 0.25\n");
  EXPECT_DOUBLE_EQ(o.regions.shadow_correction_factor, 0.5);
  EXPECT_DOUBLE_EQ(o.regions.shadow_size_correction_factor, 0.25);
  EXPECT_DOUBLE_EQ(o.regions.shadow_max_m, 3.0);
  EXPECT_DOUBLE_EQ(o.regions.shadow_bright_margin, 20.0);
  EXPECT_EQ(o.regions.shadow_min_regions, 4);
  EXPECT_DOUBLE_EQ(o.regions.shadow_agreement_px, 0.5);
  EXPECT_DOUBLE_EQ(o.regions.shadow_min_darkness, 5.0);
  EXPECT_DOUBLE_EQ(load("{}").regions.shadow_correction_factor, 1.0);  // on by default
  EXPECT_DOUBLE_EQ(load("{}").regions.shadow_size_correction_factor, 1.0);
}

TEST(SegmentationOptions, ReadsAndBoundsTheMotionEvidence) {
  const SegmentationOptions defaults = load("{}");
  EXPECT_DOUBLE_EQ(defaults.regions.motion_evidence_margin_widths, 1.0);  // on by default
  EXPECT_DOUBLE_EQ(defaults.regions.motion_evidence_max_inside, 0.6);
  EXPECT_DOUBLE_EQ(defaults.regions.motion_evidence_min_offset_px, 0.5);
  const SegmentationOptions o =
      load("motion_evidence_margin_widths: 0\nmotion_evidence_max_inside: 0.4\nmotion_evidence_min_offset_px: 1\n");
  EXPECT_DOUBLE_EQ(o.regions.motion_evidence_margin_widths, 0.0);
  EXPECT_DOUBLE_EQ(o.regions.motion_evidence_max_inside, 0.4);
  EXPECT_DOUBLE_EQ(o.regions.motion_evidence_min_offset_px, 1.0);
  expect_error_mentions("motion_evidence_margin_widths: 6\n", "motion_evidence_margin_widths");
  expect_error_mentions("motion_evidence_margin_widths: -1\n", "motion_evidence_margin_widths");
  expect_error_mentions("motion_evidence_max_inside: 1.5\n", "motion_evidence_max_inside");
  expect_error_mentions("motion_evidence_min_offset_px: .nan\n", "motion_evidence_min_offset_px");
  SegmentationOptions bad;
  bad.regions.motion_evidence_max_inside = -0.1;
  EXPECT_THROW(validate(bad), InvalidArgument);
}

TEST(SegmentationOptions, ReadsAndBoundsTheFallbackOnMotionEvidence) {
  EXPECT_DOUBLE_EQ(load("{}").regions.fallback_evidence_lengths, 0.5);  // on by default
  EXPECT_DOUBLE_EQ(load("fallback_evidence_lengths: 0\n").regions.fallback_evidence_lengths, 0.0);
  EXPECT_DOUBLE_EQ(load("fallback_evidence_lengths: 1.5\n").regions.fallback_evidence_lengths, 1.5);
  expect_error_mentions("fallback_evidence_lengths: -0.5\n", "fallback_evidence_lengths");
  expect_error_mentions("fallback_evidence_lengths: 11\n", "fallback_evidence_lengths");
  expect_error_mentions("fallback_evidence_lengths: .nan\n", "fallback_evidence_lengths");
  expect_error_mentions("fallback_evidence_lengths: far\n", "fallback_evidence_lengths");
  SegmentationOptions bad;
  bad.regions.fallback_evidence_lengths = std::nan("");
  EXPECT_THROW(validate(bad), InvalidArgument);
}

TEST(SegmentationOptions, ValidateRejectsOutOfDomainValues) {
  SegmentationOptions o;
  o.gradients.lbp_radii_px.clear();
  EXPECT_THROW(validate(o), InvalidArgument);
  o = SegmentationOptions{};
  o.regions.threshold_quantile = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(validate(o), InvalidArgument);
}

}  // namespace
}  // namespace uavmot::segmentation
