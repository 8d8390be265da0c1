#pragma once
// Shared helpers for the motion tests: where the CLIF texture lives and how to run a sequence.

#include <algorithm>
#include <numeric>
#include <string>
#include <vector>

#include "uavmot/build_paths/build_paths.hpp"
#include "uavmot/motion/motion_estimator.hpp"
#include "warped_sequence.hpp"

namespace uavmot::motion::test {

inline std::string clif_folder() { return build_paths::data_dir() + "/clif2007/jpg"; }

inline testing::WarpedSequenceOptions camera(double speed_px, double rotation_deg, cv::Size size = {960, 540}) {
  testing::WarpedSequenceOptions o;
  o.clif_folder = clif_folder();
  o.frame_size = size;
  o.camera_speed_px = speed_px;
  o.rotation_deg_per_frame = rotation_deg;
  return o;
}

inline Frame make_frame(const cv::Mat& image, int k) {
  Frame f;
  f.stream_id = "test";
  f.index = k;
  f.capture_time_ns = static_cast<int64_t>(k) * 40'000'000;
  f.image = image;
  return f;
}

inline std::vector<MotionEstimate> run(const testing::WarpedSequence& sequence, int frames,
                                       const MotionOptions& options = {}) {
  MotionEstimator estimator(options);
  std::vector<MotionEstimate> out;
  for (int k = 1; k <= frames; ++k) out.push_back(estimator.process(make_frame(sequence.frame(k), k)));
  return out;
}

// Homographies against the truth: mean and worst frame of the mean transfer error, valid frames.
struct ErrorStats {
  double mean = 0, max = 0;
  int valid = 0;
};

// Transfer error of every valid estimate after the first against the sequence's exact homography.
inline ErrorStats transfer_errors(const testing::WarpedSequence& sequence, const std::vector<MotionEstimate>& estimates) {
  ErrorStats s;
  std::vector<double> per_frame;
  const cv::Size size = sequence.options().frame_size;
  for (size_t i = 1; i < estimates.size(); ++i) {
    const auto& e = estimates[i];
    if (!e.quality.valid) continue;
    ++s.valid;
    per_frame.push_back(mean_transfer_error(e.homography, sequence.true_homography(static_cast<int>(e.frame_index)),
                                            size.width, size.height));
  }
  if (per_frame.empty()) return s;
  s.mean = std::accumulate(per_frame.begin(), per_frame.end(), 0.0) / static_cast<double>(per_frame.size());
  s.max = *std::max_element(per_frame.begin(), per_frame.end());
  return s;
}

}  // namespace uavmot::motion::test
