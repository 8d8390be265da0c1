#pragma once
// The motion model (the predictor): how a track's Kalman state moves from frame k-1 to frame k,
// given the camera's frame-to-frame homography. TrackerOptions::motion_model picks one by name from
// the list in motion_model.cpp; each model lives in its own file in motion_models/.
// Adding one: docs/developing.md, "Worked example: add a motion model".

#include <memory>
#include <string>
#include <vector>

#include "kalman_model.hpp"
#include "uavmot/core/homography.hpp"
#include "uavmot/tracking/tracker_options.hpp"

namespace uavmot::tracking {

class MotionModel {
 public:
  virtual ~MotionModel() = default;
  // The prior of frame k from the posterior of frame k-1. `h` maps frame k-1 to frame k; it is
  // always usable (finite, h33 = 1; the tracker substitutes the identity for a broken one).
  // The state layout is kalman_model.hpp's; the result must be deterministic.
  virtual KalmanState predict(const KalmanState& posterior, const Homography& h) const = 0;
};

// Builds a model from the options (its noise parameters).
using MotionModelFactory = std::unique_ptr<MotionModel> (*)(const TrackerOptions& options);

// The names TrackerOptions::motion_model accepts, in the order they are listed.
std::vector<std::string> motion_model_names();

// The model TrackerOptions::motion_model names; throws uavmot::InvalidArgument for an unknown name.
std::unique_ptr<MotionModel> make_motion_model(const TrackerOptions& options);

}  // namespace uavmot::tracking
