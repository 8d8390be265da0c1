#pragma once
// The Kalman filter's state and noise models (paper IV-D): an oriented box (centre, width, length,
// axis angle) moving with constant ground velocity. State layout in tracker_state.hpp.

#include <Eigen/Core>

#include "uavmot/core/oriented_box.hpp"
#include "uavmot/tracking/tracker_options.hpp"
#include "uavmot/tracking/tracker_state.hpp"

namespace uavmot::tracking {

using StateVector = Eigen::Matrix<double, kStateSize, 1>;
using StateCovariance = Eigen::Matrix<double, kStateSize, kStateSize>;

enum StateIndex : int { kX = 0, kY = 1, kVx = 2, kVy = 3, kWidth = 4, kLength = 5, kAngle = 6 };

struct KalmanState {
  StateVector mean = StateVector::Zero();
  StateCovariance covariance = StateCovariance::Identity();
};

struct ProcessNoise {
  double accel_sigma_px = 0.08;
  double size_sigma_px = 0.05;
  double angle_sigma_deg = 1.0;
};

struct BoxMeasurementNoise {
  double position_sigma_px = 1.0;
  double size_sigma_px = 1.5;
  double angle_sigma_deg = 5.0;
  double min_elongation_for_angle = 1.25;
  double ambiguous_angle_sigma_deg = 45.0;
};

ProcessNoise process_noise(const TrackerOptions& options);

// Q for one frame (dt = 1): piecewise-constant white acceleration on centre and velocity per axis,
// random walk on width, length and angle.
StateCovariance process_noise_covariance(const ProcessNoise& noise);
BoxMeasurementNoise box_measurement_noise(const TrackerOptions& options);

// A new track from a region: position and size from the box, velocity from `velocity` with
// 1-sigma `velocity_sigma` per axis.
KalmanState initial_state(const OrientedBox& box, const cv::Vec2d& velocity, double velocity_sigma,
                          const BoxMeasurementNoise& noise);

OrientedBox box_of(const StateVector& mean);
cv::Vec2d velocity_of(const StateVector& mean);

KalmanState to_kalman(const TrackRecord& record);
void store(const KalmanState& kalman, TrackRecord& record);
bool is_finite(const KalmanState& kalman);

}  // namespace uavmot::tracking
