#pragma once
// Kalman prediction with the frame-to-frame homography as control input (paper IV-D).
// An object at p with ground velocity v (frame k-1) is at p + v on the ground one frame later;
// the camera maps that to H(p + v) in frame k. Its velocity in frame k is H(p + v) - H(p), and its box
// axes are carried by the homography's local Jacobian. The covariance is propagated with the
// Jacobian of this whole transition (an extended Kalman filter), plus process noise.

#include "uavmot/core/homography.hpp"
#include "kalman_model.hpp"

namespace uavmot::tracking {

// The noise-free transition of the state from frame k-1 to frame k.
StateVector transition(const StateVector& mean, const Homography& h);

// d transition / d state at `mean` (central differences; angle outputs compared modulo 180 deg).
StateCovariance transition_jacobian(const StateVector& mean, const Homography& h);

KalmanState predict(const KalmanState& state, const Homography& h, const ProcessNoise& noise);

}  // namespace uavmot::tracking
