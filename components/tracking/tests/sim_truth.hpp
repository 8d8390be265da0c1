#pragma once
// The simulator's ground truth turned into the tracker's input, for scenario tests that do not
// depend on the motion and segmentation layers: the exact frame-to-frame homography, features at
// fixed places on every visible vehicle (with noise; moving as the truth says), and one region per
// moving vehicle (true footprint plus noise, vehicles closer than `merge_gap_px` merged into one
// region, some regions missed). Scored like the paper's Table I/II (paper_score).
// Built only when the simulator (components/sim) is in the tree.

#include <cstdint>
#include <map>
#include <random>
#include <vector>

#include "uavmot/sim/simulator.hpp"
#include "uavmot/tracking/tracker.hpp"

namespace uavmot::tracking::testing {

struct TruthMeasurementOptions {
  int features_per_vehicle = 8;
  double feature_position_noise_px = 0.2;
  double feature_velocity_noise = 0.1;
  double region_position_noise_px = 0.7;
  double region_size_noise_px = 0.8;
  double region_angle_noise_deg = 3.0;
  double region_miss_probability = 0.1;
  double merge_gap_px = 1.5;
  double min_visibility = 0.6;
  uint32_t seed = 7;
};

class TruthMeasurements {
 public:
  explicit TruthMeasurements(TruthMeasurementOptions options = {});
  void make(const sim::SimFrame& frame, MotionEstimate& motion, SegmentationResult& segmentation);
  int merged_regions() const { return merged_regions_; }

 private:
  TruthMeasurementOptions options_;
  std::mt19937 rng_;
  std::map<int, std::vector<cv::Point2d>> feature_uv_;
  int merged_regions_ = 0;
};

// Completeness and precision as in the paper (Tables I, II), over moving vehicles fully in view:
// correct = exactly one box covers the vehicle (>= 30 % of its footprint) and that box covers no
// other moving vehicle; errors are means over correct instances.
struct PaperScore {
  int instances = 0;
  int correct = 0;
  int under = 0;
  int over = 0;
  int missed = 0;
  double position_error = 0.0;
  double width_error = 0.0;
  double length_error = 0.0;
  int id_switches = 0;
  int moving_vehicles_tracked = 0;
  int parked_track_frames = 0;  // confirmed track-frames on a parked vehicle
  int false_track_frames = 0;   // confirmed track-frames on no vehicle
  double rate(int n) const { return instances > 0 ? static_cast<double>(n) / instances : 0.0; }
};

class PaperScorer {
 public:
  void add(const sim::SimFrame& frame, const std::vector<OrientedBox>& boxes, const std::vector<uint64_t>& ids);
  PaperScore result() const;

 private:
  PaperScore score_;
  int error_count_ = 0;
  std::map<int, std::vector<uint64_t>> ids_of_vehicle_;
};

// Runs `frames` frames of a preset through the tracker (image size set from the scenario); scoring
// starts at `score_from`.
PaperScore run_sim_truth(const std::string& preset, int frames, uint64_t seed, const TruthMeasurementOptions& measurements,
                         TrackerOptions options = {}, int score_from = 15);

}  // namespace uavmot::tracking::testing
