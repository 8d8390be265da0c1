#include "uavmot/segmentation/segmentation_options.hpp"

#include <cmath>
#include <string>

#include "uavmot/core/error.hpp"

namespace uavmot::segmentation {
namespace {

void require(bool ok, const std::string& field, const std::string& domain) {
  if (!ok) throw InvalidArgument("segmentation option " + field + " must be " + domain);
}

bool in_range(double v, double lo, double hi) { return std::isfinite(v) && v >= lo && v <= hi; }

template <typename T>
std::vector<T> read_number_list(const ConfigNode& node, const std::string& key, std::vector<T> fallback, T lo, T hi) {
  if (!node.has(key)) return fallback;
  const YAML::Node list = node.yaml()[key];
  if (!list.IsSequence() || list.size() == 0) node.fail(key, "expected a non-empty list of numbers");
  std::vector<T> values;
  for (size_t i = 0; i < list.size(); ++i) {
    T value{};
    try {
      value = list[i].as<T>();
    } catch (const YAML::Exception&) {
      node.fail(key, "entry " + std::to_string(i) + " is not a number");
    }
    if (!(value >= lo && value <= hi)) {
      node.fail(key, "entry " + std::to_string(i) + " must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
    }
    values.push_back(value);
  }
  return values;
}

}  // namespace

void validate(const SegmentationOptions& o) {
  const auto& c = o.clustering;
  require(in_range(c.link_distance_m, 0.01, 1000.0), "link_distance_m", "in [0.01, 1000]");
  require(in_range(c.link_speed_difference_mps, 0.0, 1000.0), "link_speed_difference_mps", "in [0, 1000]");
  require(in_range(c.velocity_sigma_factor, 0.0, 100.0), "velocity_sigma_factor", "in [0, 100]");
  require(c.min_features >= 1, "min_features", ">= 1");

  const auto& g = o.gradients;
  require(!g.korn_sigmas_px.empty(), "korn_sigmas_px", "non-empty");
  for (double s : g.korn_sigmas_px) require(in_range(s, 0.3, 20.0), "korn_sigmas_px", "in [0.3, 20]");
  require(!g.morphological_sizes_px.empty(), "morphological_sizes_px", "non-empty");
  for (int s : g.morphological_sizes_px) require(s >= 3 && s <= 41 && s % 2 == 1, "morphological_sizes_px", "odd in [3, 41]");
  require(g.lbp_neighbours >= 4 && g.lbp_neighbours <= 32, "lbp_neighbours", "in [4, 32]");
  require(!g.lbp_radii_px.empty(), "lbp_radii_px", "non-empty");
  for (double r : g.lbp_radii_px) require(in_range(r, 1.0, 10.0), "lbp_radii_px", "in [1, 10]");
  require(in_range(g.lbp_min_stddev, 0.0, 255.0), "lbp_min_stddev", "in [0, 255]");

  const auto& r = o.regions;
  require(in_range(r.window_margin_m, 0.0, 1000.0), "window_margin_m", "in [0, 1000]");
  require(in_range(r.min_edge_contrast, 0.1, 255.0), "min_edge_contrast", "in [0.1, 255]");
  require(in_range(r.threshold_quantile, 0.0, 1.0), "threshold_quantile", "in [0, 1]");
  require(in_range(r.threshold_min_fraction, 0.0, 1.0), "threshold_min_fraction", "in [0, 1]");
  require(r.connectivity == 0 || r.connectivity == 4 || r.connectivity == 8, "connectivity", "0, 4 or 8");
  require(r.closing_size_px >= 1 && r.closing_size_px <= 31 && r.closing_size_px % 2 == 1, "closing_size_px", "odd in [1, 31]");
  require(in_range(r.edge_band_px, 0.0, 10.0), "edge_band_px", "in [0, 10]");
  require(in_range(r.split_width_factor, 0.0, 100.0), "split_width_factor", "in [0, 100]");
  require(in_range(r.split_length_factor, 0.0, 100.0), "split_length_factor", "in [0, 100]");
  require(in_range(r.group_length_factor, 0.0, 100.0), "group_length_factor", "in [0, 100]");
  require(in_range(r.group_width_factor, 0.0, 100.0), "group_width_factor", "in [0, 100]");
  require(in_range(r.group_touch_px, 0.0, 100.0), "group_touch_px", "in [0, 100]");
  require(in_range(r.recentre_min_offset_fraction, 0.0, 1.0), "recentre_min_offset_fraction", "in [0, 1]");
  require(in_range(r.motion_evidence_margin_widths, 0.0, 5.0), "motion_evidence_margin_widths", "in [0, 5]");
  require(in_range(r.motion_evidence_max_inside, 0.0, 1.0), "motion_evidence_max_inside", "in [0, 1]");
  require(in_range(r.motion_evidence_min_offset_px, 0.0, 100.0), "motion_evidence_min_offset_px", "in [0, 100]");
  require(in_range(r.fallback_evidence_lengths, 0.0, 10.0), "fallback_evidence_lengths", "in [0, 10]");
  require(in_range(r.fallback_evidence_widths, 0.0, 10.0), "fallback_evidence_widths", "in [0, 10]");
  require(in_range(r.fallback_evidence_max_ratio, 0.0, 10.0), "fallback_evidence_max_ratio", "in [0, 10]");
  require(in_range(r.min_length_factor, 0.0, 100.0), "min_length_factor", "in [0, 100]");
  require(in_range(r.max_length_factor, r.min_length_factor, 100.0), "max_length_factor", "in [min_length_factor, 100]");
  require(in_range(r.min_width_factor, 0.0, 100.0), "min_width_factor", "in [0, 100]");
  require(in_range(r.max_width_factor, r.min_width_factor, 100.0), "max_width_factor", "in [min_width_factor, 100]");
  require(r.min_supporting_features >= 0, "min_supporting_features", ">= 0");
  require(in_range(r.support_margin_px, 0.0, 100.0), "support_margin_px", "in [0, 100]");
  require(in_range(r.duplicate_overlap, 0.0, 1.0), "duplicate_overlap", "in [0, 1]");
  require(in_range(r.shift_check_ratio, 0.0, 10.0), "shift_check_ratio", "in [0, 10]");
  require(in_range(r.shift_check_min_speed_px, 0.0, 100.0), "shift_check_min_speed_px", "in [0, 100]");
  require(in_range(r.shift_check_search_px, 0.0, 10.0), "shift_check_search_px", "in [0, 10]");
  require(in_range(r.shadow_correction_factor, 0.0, 2.0), "shadow_correction_factor", "in [0, 2]");
  require(in_range(r.shadow_size_correction_factor, 0.0, 2.0), "shadow_size_correction_factor", "in [0, 2]");
  require(in_range(r.shadow_max_m, 0.0, 20.0), "shadow_max_m", "in [0, 20]");
  require(in_range(r.shadow_bright_margin, 0.0, 255.0), "shadow_bright_margin", "in [0, 255]");
  require(r.shadow_min_regions >= 1 && r.shadow_min_regions <= 100000, "shadow_min_regions", "in [1, 100000]");
  require(in_range(r.shadow_agreement_px, 0.0, 100.0), "shadow_agreement_px", "in [0, 100]");
  require(in_range(r.shadow_min_darkness, 0.0, 255.0), "shadow_min_darkness", "in [0, 255]");
}

SegmentationOptions load_segmentation_options(const ConfigNode& node) {
  SegmentationOptions o;
  node.expect_only({"method", "link_distance_m", "link_speed_difference_mps", "velocity_sigma_factor", "min_features",
                    "korn_sigmas_px", "morphological_sizes_px", "lbp_neighbours", "lbp_radii_px", "lbp_min_stddev",
                    "window_margin_m", "min_edge_contrast", "fusion_rule", "threshold_quantile",
                    "threshold_min_fraction", "connectivity", "closing_size_px", "box_fit", "edge_band_px", "split_width_factor", "split_length_factor", "group_length_factor", "group_width_factor", "group_touch_px", "recentre_min_offset_fraction", "motion_evidence_margin_widths", "motion_evidence_max_inside", "motion_evidence_min_offset_px", "fallback_evidence_lengths", "fallback_evidence_widths", "fallback_evidence_max_ratio", "min_length_factor",
                    "max_length_factor", "min_width_factor", "max_width_factor", "min_supporting_features",
                    "support_margin_px", "fallback_to_cluster_box", "duplicate_overlap", "shift_check_ratio",
                    "shift_check_min_speed_px", "shift_check_search_px", "shadow_correction_factor", "shadow_size_correction_factor", "shadow_max_m",
                    "shadow_bright_margin", "shadow_min_regions", "shadow_agreement_px", "shadow_min_darkness"});
  std::string method = to_string(o.method);
  node.read_choice("method", method, segmentation_method_names());
  o.method = parse_segmentation_method(method);

  auto& c = o.clustering;
  node.read("link_distance_m", c.link_distance_m, 0.01, 1000.0);
  node.read("link_speed_difference_mps", c.link_speed_difference_mps, 0.0, 1000.0);
  node.read("velocity_sigma_factor", c.velocity_sigma_factor, 0.0, 100.0);
  node.read("min_features", c.min_features, 1, 1000000);

  auto& g = o.gradients;
  g.korn_sigmas_px = read_number_list<double>(node, "korn_sigmas_px", g.korn_sigmas_px, 0.3, 20.0);
  g.morphological_sizes_px = read_number_list<int>(node, "morphological_sizes_px", g.morphological_sizes_px, 3, 41);
  for (int s : g.morphological_sizes_px) {
    if (s % 2 == 0) node.fail("morphological_sizes_px", "sizes must be odd, got " + std::to_string(s));
  }
  node.read("lbp_neighbours", g.lbp_neighbours, 4, 32);
  g.lbp_radii_px = read_number_list<double>(node, "lbp_radii_px", g.lbp_radii_px, 1.0, 10.0);
  node.read("lbp_min_stddev", g.lbp_min_stddev, 0.0, 255.0);

  auto& r = o.regions;
  node.read("window_margin_m", r.window_margin_m, 0.0, 1000.0);
  node.read("min_edge_contrast", r.min_edge_contrast, 0.1, 255.0);
  std::string rule = r.fusion_rule == FusionRule::Sum ? "sum" : "product";
  node.read_choice("fusion_rule", rule, {"sum", "product"});
  r.fusion_rule = rule == "sum" ? FusionRule::Sum : FusionRule::Product;
  node.read("threshold_quantile", r.threshold_quantile, 0.0, 1.0);
  node.read("threshold_min_fraction", r.threshold_min_fraction, 0.0, 1.0);
  node.read("connectivity", r.connectivity, 0, 8);
  if (r.connectivity != 0 && r.connectivity != 4 && r.connectivity != 8) node.fail("connectivity", "must be 0 (by method), 4 or 8");
  node.read("closing_size_px", r.closing_size_px, 1, 31);
  if (r.closing_size_px % 2 == 0) node.fail("closing_size_px", "must be odd");
  std::string fit = r.box_fit == BoxFit::Moments ? "moments" : "min_area_rect";
  node.read_choice("box_fit", fit, {"moments", "min_area_rect"});
  r.box_fit = fit == "moments" ? BoxFit::Moments : BoxFit::MinAreaRect;
  node.read("edge_band_px", r.edge_band_px, 0.0, 10.0);
  node.read("split_width_factor", r.split_width_factor, 0.0, 100.0);
  node.read("split_length_factor", r.split_length_factor, 0.0, 100.0);
  node.read("group_length_factor", r.group_length_factor, 0.0, 100.0);
  node.read("group_width_factor", r.group_width_factor, 0.0, 100.0);
  node.read("group_touch_px", r.group_touch_px, 0.0, 100.0);
  node.read("recentre_min_offset_fraction", r.recentre_min_offset_fraction, 0.0, 1.0);
  node.read("motion_evidence_margin_widths", r.motion_evidence_margin_widths, 0.0, 5.0);
  node.read("motion_evidence_max_inside", r.motion_evidence_max_inside, 0.0, 1.0);
  node.read("motion_evidence_min_offset_px", r.motion_evidence_min_offset_px, 0.0, 100.0);
  node.read("fallback_evidence_lengths", r.fallback_evidence_lengths, 0.0, 10.0);
  node.read("fallback_evidence_widths", r.fallback_evidence_widths, 0.0, 10.0);
  node.read("fallback_evidence_max_ratio", r.fallback_evidence_max_ratio, 0.0, 10.0);
  node.read("min_length_factor", r.min_length_factor, 0.0, 100.0);
  node.read("max_length_factor", r.max_length_factor, 0.0, 100.0);
  node.read("min_width_factor", r.min_width_factor, 0.0, 100.0);
  node.read("max_width_factor", r.max_width_factor, 0.0, 100.0);
  if (r.max_length_factor < r.min_length_factor) node.fail("max_length_factor", "must be >= min_length_factor");
  if (r.max_width_factor < r.min_width_factor) node.fail("max_width_factor", "must be >= min_width_factor");
  node.read("min_supporting_features", r.min_supporting_features, 0, 1000000);
  node.read("support_margin_px", r.support_margin_px, 0.0, 100.0);
  node.read("fallback_to_cluster_box", r.fallback_to_cluster_box);
  node.read("duplicate_overlap", r.duplicate_overlap, 0.0, 1.0);
  node.read("shift_check_ratio", r.shift_check_ratio, 0.0, 10.0);
  node.read("shift_check_min_speed_px", r.shift_check_min_speed_px, 0.0, 100.0);
  node.read("shift_check_search_px", r.shift_check_search_px, 0.0, 10.0);
  node.read("shadow_correction_factor", r.shadow_correction_factor, 0.0, 2.0);
  node.read("shadow_size_correction_factor", r.shadow_size_correction_factor, 0.0, 2.0);
  node.read("shadow_max_m", r.shadow_max_m, 0.0, 20.0);
  node.read("shadow_bright_margin", r.shadow_bright_margin, 0.0, 255.0);
  node.read("shadow_min_regions", r.shadow_min_regions, 1, 100000);
  node.read("shadow_agreement_px", r.shadow_agreement_px, 0.0, 100.0);
  node.read("shadow_min_darkness", r.shadow_min_darkness, 0.0, 255.0);
  validate(o);
  return o;
}

}  // namespace uavmot::segmentation
