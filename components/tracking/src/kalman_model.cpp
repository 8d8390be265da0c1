#include "kalman_model.hpp"

#include <cmath>
#include <utility>

namespace uavmot::tracking {

ProcessNoise process_noise(const TrackerOptions& options) {
  return {options.process_accel_sigma_px, options.process_size_sigma_px, options.process_angle_sigma_deg};
}

StateCovariance process_noise_covariance(const ProcessNoise& noise) {
  StateCovariance q = StateCovariance::Zero();
  const double a2 = noise.accel_sigma_px * noise.accel_sigma_px;
  for (const auto& [pos, vel] : {std::pair{kX, kVx}, std::pair{kY, kVy}}) {
    q(pos, pos) = 0.25 * a2;
    q(pos, vel) = q(vel, pos) = 0.5 * a2;
    q(vel, vel) = a2;
  }
  q(kWidth, kWidth) = q(kLength, kLength) = noise.size_sigma_px * noise.size_sigma_px;
  q(kAngle, kAngle) = noise.angle_sigma_deg * noise.angle_sigma_deg;
  return q;
}

BoxMeasurementNoise box_measurement_noise(const TrackerOptions& options) {
  return {options.region_position_sigma_px, options.region_size_sigma_px, options.region_angle_sigma_deg,
          options.min_elongation_for_angle, options.ambiguous_angle_sigma_deg};
}

KalmanState initial_state(const OrientedBox& box, const cv::Vec2d& velocity, double velocity_sigma,
                          const BoxMeasurementNoise& noise) {
  KalmanState s;
  s.mean << box.cx, box.cy, velocity[0], velocity[1], box.width, box.length, normalize_axis_angle_deg(box.angle_deg);
  const bool ambiguous = box.length < noise.min_elongation_for_angle * box.width;
  const double angle_sigma = ambiguous ? noise.ambiguous_angle_sigma_deg : noise.angle_sigma_deg;
  s.covariance.setZero();
  s.covariance(kX, kX) = s.covariance(kY, kY) = noise.position_sigma_px * noise.position_sigma_px;
  s.covariance(kVx, kVx) = s.covariance(kVy, kVy) = velocity_sigma * velocity_sigma;
  s.covariance(kWidth, kWidth) = s.covariance(kLength, kLength) = noise.size_sigma_px * noise.size_sigma_px;
  s.covariance(kAngle, kAngle) = angle_sigma * angle_sigma;
  return s;
}

OrientedBox box_of(const StateVector& mean) {
  return OrientedBox{mean(kX), mean(kY), mean(kWidth), mean(kLength), mean(kAngle)};
}

cv::Vec2d velocity_of(const StateVector& mean) { return {mean(kVx), mean(kVy)}; }

KalmanState to_kalman(const TrackRecord& record) {
  KalmanState s;
  for (int i = 0; i < kStateSize; ++i) {
    s.mean(i) = record.mean[static_cast<size_t>(i)];
    for (int j = 0; j < kStateSize; ++j) s.covariance(i, j) = record.covariance[static_cast<size_t>(i * kStateSize + j)];
  }
  return s;
}

void store(const KalmanState& kalman, TrackRecord& record) {
  for (int i = 0; i < kStateSize; ++i) {
    record.mean[static_cast<size_t>(i)] = kalman.mean(i);
    for (int j = 0; j < kStateSize; ++j) record.covariance[static_cast<size_t>(i * kStateSize + j)] = kalman.covariance(i, j);
  }
}

bool is_finite(const KalmanState& kalman) { return kalman.mean.allFinite() && kalman.covariance.allFinite(); }

}  // namespace uavmot::tracking
