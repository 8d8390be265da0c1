#include "uavmot/tracking/tracker_options.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "uavmot/core/chain_types.hpp"
#include "motion_model.hpp"
#include "uavmot/core/error.hpp"
#include "uavmot/core/segmentation_method.hpp"

namespace uavmot::tracking {
namespace {

// "auto", "all", then every segmentation method (core/segmentation_method.hpp keeps the list).
const std::vector<std::string>& region_method_choices() {
  static const std::vector<std::string> choices = [] {
    std::vector<std::string> names = {"auto", "all"};
    for (const std::string& name : segmentation_method_names()) names.push_back(name);
    return names;
  }();
  return choices;
}

// One table drives both the YAML reader and validate(), so the ranges cannot disagree.
struct DoubleField {
  const char* key;
  double TrackerOptions::*member;
  double min;
  double max;
};
struct IntField {
  const char* key;
  int TrackerOptions::*member;
  int min;
  int max;
};

const std::vector<DoubleField>& double_fields() {
  static const std::vector<DoubleField> fields = {
      {"confirm_min_speed_mps", &TrackerOptions::confirm_min_speed_mps, 0.0, 100.0},
      {"confirm_border_margin_px", &TrackerOptions::confirm_border_margin_px, 0.0, 1000.0},
      {"confirm_entering_max_angle_deg", &TrackerOptions::confirm_entering_max_angle_deg, 0.0, 90.0},
      {"process_accel_sigma_px", &TrackerOptions::process_accel_sigma_px, 1e-6, 100.0},
      {"process_size_sigma_px", &TrackerOptions::process_size_sigma_px, 1e-6, 100.0},
      {"process_angle_sigma_deg", &TrackerOptions::process_angle_sigma_deg, 1e-6, 90.0},
      {"region_position_sigma_px", &TrackerOptions::region_position_sigma_px, 1e-3, 1000.0},
      {"region_size_sigma_px", &TrackerOptions::region_size_sigma_px, 1e-3, 1000.0},
      {"region_angle_sigma_deg", &TrackerOptions::region_angle_sigma_deg, 1e-3, 180.0},
      {"min_elongation_for_angle", &TrackerOptions::min_elongation_for_angle, 1.0, 10.0},
      {"ambiguous_angle_sigma_deg", &TrackerOptions::ambiguous_angle_sigma_deg, 1e-3, 1000.0},
      {"reconstruction_sigma_px", &TrackerOptions::reconstruction_sigma_px, 1e-3, 1000.0},
      {"init_velocity_sigma", &TrackerOptions::init_velocity_sigma, 1e-3, 1000.0},
      {"init_velocity_sigma_features", &TrackerOptions::init_velocity_sigma_features, 1e-3, 1000.0},
      {"min_box_size_px", &TrackerOptions::min_box_size_px, 1e-3, 1000.0},
      {"min_intersection_fraction", &TrackerOptions::min_intersection_fraction, 0.0, 1.0},
      {"feature_motion_abs_tolerance", &TrackerOptions::feature_motion_abs_tolerance, 0.0, 1000.0},
      {"feature_motion_rel_tolerance", &TrackerOptions::feature_motion_rel_tolerance, 0.0, 10.0},
      {"feature_direction_tolerance_deg", &TrackerOptions::feature_direction_tolerance_deg, 0.0, 180.0},
      {"feature_min_speed_for_direction", &TrackerOptions::feature_min_speed_for_direction, 0.0, 1000.0},
      {"feature_position_margin", &TrackerOptions::feature_position_margin, 0.0, 10.0},
      {"feature_reconstruction_outlier_px", &TrackerOptions::feature_reconstruction_outlier_px, 1e-3, 1000.0},
      {"feature_uv_smoothing", &TrackerOptions::feature_uv_smoothing, 0.0, 1.0},
      {"feature_velocity_sigma_px", &TrackerOptions::feature_velocity_sigma_px, 0.0, 100.0},
      {"heading_min_speed_px", &TrackerOptions::heading_min_speed_px, 0.0, 1000.0},
      {"heading_sigma_deg", &TrackerOptions::heading_sigma_deg, 0.0, 180.0},
      {"travel_heading_min_lengths", &TrackerOptions::travel_heading_min_lengths, 0.0, 1000.0},
      {"travel_heading_max_turn_deg", &TrackerOptions::travel_heading_max_turn_deg, 0.0, 180.0},
      {"travel_heading_max_lengths", &TrackerOptions::travel_heading_max_lengths, 0.0, 1000.0},
      {"feature_span_margin_px", &TrackerOptions::feature_span_margin_px, -1.0, 100.0},
      {"link_min_length_factor", &TrackerOptions::link_min_length_factor, 0.0, 10.0},
      {"stopped_link_min_travel_lengths", &TrackerOptions::stopped_link_min_travel_lengths, 0.0, 1000.0},
      {"fragment_union_factor", &TrackerOptions::fragment_union_factor, 1.0, 10.0},
      {"single_object_size_factor", &TrackerOptions::single_object_size_factor, 0.0, 100.0},
      {"piece_max_gap_m", &TrackerOptions::piece_max_gap_m, 0.0, 100.0},
      {"piece_min_speed_mps", &TrackerOptions::piece_min_speed_mps, 0.0, 1000.0},
      {"piece_max_speed_difference_mps", &TrackerOptions::piece_max_speed_difference_mps, 0.0, 1000.0},
      {"piece_max_turn_rate_dps", &TrackerOptions::piece_max_turn_rate_dps, 0.0, 360.0},
      {"piece_max_lateral_m", &TrackerOptions::piece_max_lateral_m, 0.0, 100.0},
      {"max_object_width_m", &TrackerOptions::max_object_width_m, 0.1, 100.0},
      {"max_object_length_factor", &TrackerOptions::max_object_length_factor, 0.1, 100.0},
      {"max_region_width_m", &TrackerOptions::max_region_width_m, 0.0, 100.0},
      {"init_max_overlap_fraction", &TrackerOptions::init_max_overlap_fraction, 0.0, 1.0},
      {"min_region_area_px", &TrackerOptions::min_region_area_px, 0.0, 1e6},
      {"reacquire_radius_m", &TrackerOptions::reacquire_radius_m, 0.0, 1000.0},
      {"reacquire_lateral_m", &TrackerOptions::reacquire_lateral_m, 0.0, 1000.0},
      {"reacquire_size_ratio", &TrackerOptions::reacquire_size_ratio, 1.0, 100.0},
  };
  return fields;
}

const std::vector<IntField>& int_fields() {
  static const std::vector<IntField> fields = {
      {"max_features_per_track", &TrackerOptions::max_features_per_track, 0, 1000},
      {"min_reconstruction_features", &TrackerOptions::min_reconstruction_features, 1, 1000},
      {"stopped_link_min_frames", &TrackerOptions::stopped_link_min_frames, 0, 1000000},
      {"confirm_hits", &TrackerOptions::confirm_hits, 1, 32},
      {"confirm_window", &TrackerOptions::confirm_window, 1, 32},
      {"confirm_hits_with_features", &TrackerOptions::confirm_hits_with_features, 0, 32},
      {"confirm_min_features", &TrackerOptions::confirm_min_features, 1, 1000},
      {"quick_confirm_min_features", &TrackerOptions::quick_confirm_min_features, 1, 1000},
      {"confirm_entering_min_features", &TrackerOptions::confirm_entering_min_features, 0, 1000},
      {"quick_confirm_max_ground_frames", &TrackerOptions::quick_confirm_max_ground_frames, -1, 1000},
      {"tentative_max_misses", &TrackerOptions::tentative_max_misses, 0, 1000},
      {"max_coast_frames", &TrackerOptions::max_coast_frames, 0, 100000},
      {"gap_frames", &TrackerOptions::gap_frames, 0, 100000},
      {"gap_min_hits", &TrackerOptions::gap_min_hits, 0, 1000000},
      {"reacquire_max_frames", &TrackerOptions::reacquire_max_frames, 0, 1000000},
      {"image_width", &TrackerOptions::image_width, 0, 1000000},
      {"image_height", &TrackerOptions::image_height, 0, 1000000},
  };
  return fields;
}

}  // namespace

TrackerOptions load_tracker_options(const ConfigNode& node) {
  TrackerOptions options;
  std::vector<std::string> known = {"region_method", "motion_model"};
  for (const auto& f : double_fields()) known.emplace_back(f.key);
  for (const auto& f : int_fields()) known.emplace_back(f.key);
  node.expect_only(known);
  node.read_choice("region_method", options.region_method, region_method_choices());
  node.read_choice("motion_model", options.motion_model, motion_model_names());
  for (const auto& f : double_fields()) node.read(f.key, options.*(f.member), f.min, f.max);
  for (const auto& f : int_fields()) node.read(f.key, options.*(f.member), f.min, f.max);
  if (options.confirm_hits > options.confirm_window) {
    node.fail("confirm_hits", "must not exceed confirm_window (" + std::to_string(options.confirm_window) + ")");
  }
  return options;
}

void validate(const TrackerOptions& options) {
  bool known_method = false;
  for (const auto& choice : region_method_choices()) known_method = known_method || choice == options.region_method;
  if (!known_method) throw InvalidArgument("tracking.region_method: unknown value '" + options.region_method + "'");
  const std::vector<std::string> models = motion_model_names();
  if (std::find(models.begin(), models.end(), options.motion_model) == models.end()) {
    throw InvalidArgument("tracking.motion_model: unknown value '" + options.motion_model + "'");
  }
  for (const auto& f : double_fields()) {
    const double v = options.*(f.member);
    if (!std::isfinite(v) || v < f.min || v > f.max) {
      throw InvalidArgument(std::string("tracking.") + f.key + ": value " + std::to_string(v) + " is outside [" +
                            std::to_string(f.min) + ", " + std::to_string(f.max) + "]");
    }
  }
  for (const auto& f : int_fields()) {
    const int v = options.*(f.member);
    if (v < f.min || v > f.max) {
      throw InvalidArgument(std::string("tracking.") + f.key + ": value " + std::to_string(v) + " is outside [" +
                            std::to_string(f.min) + ", " + std::to_string(f.max) + "]");
    }
  }
  if (options.confirm_hits > options.confirm_window) {
    throw InvalidArgument("tracking.confirm_hits must not exceed tracking.confirm_window");
  }
}

}  // namespace uavmot::tracking
