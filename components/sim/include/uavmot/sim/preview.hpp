#pragma once
// A colour picture of one simulated frame with its ground truth drawn on it, for people to
// judge realism: moving vehicles green (with velocity), stopped vehicles yellow, parked blue;
// silhouettes of buildings and walls magenta, of trees pale green.

#include <opencv2/core/mat.hpp>
#include <opencv2/core/types.hpp>

#include "uavmot/sim/simulator.hpp"

namespace uavmot::sim {

struct PreviewOptions {
  double scale = 1.0;       // enlarge (e.g. 2) so small vehicles can be seen
  cv::Rect crop;            // part of the frame to show (before scaling); empty = all
  bool draw_ids = true;
  bool draw_velocity = true;
  bool draw_structures = true;
  double velocity_gain = 10.0;  // arrow length in frames of motion
};

cv::Mat draw_ground_truth(const SimFrame& frame, const PreviewOptions& options = {});

}  // namespace uavmot::sim
