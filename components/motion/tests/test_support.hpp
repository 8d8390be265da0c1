#pragma once
// Shared helpers for the motion tests: where the CLIF texture lives and how to run a sequence.

#include <string>
#include <vector>

#include "uavmot/motion/motion_estimator.hpp"
#include "warped_sequence.hpp"

namespace uavmot::motion::test {

inline std::string clif_folder() { return std::string(UAVMOT_DATA_DIR) + "/clif2007/jpg"; }

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

}  // namespace uavmot::motion::test
