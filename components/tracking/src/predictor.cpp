#include "predictor.hpp"

#include <algorithm>
#include <cmath>

namespace uavmot::tracking {

StateVector transition(const StateVector& mean, const Homography& h) {
  const cv::Point2d p(mean(kX), mean(kY));
  const cv::Point2d moved(p.x + mean(kVx), p.y + mean(kVy));  // on the ground, still in frame k-1 coordinates
  const OrientedBox moved_box{moved.x, moved.y, mean(kWidth), mean(kLength), mean(kAngle)};
  const OrientedBox out_box = transform_box(h, moved_box);
  const cv::Point2d p_now = apply_homography(h, p);  // where the object was, seen from frame k
  StateVector out;
  out << out_box.cx, out_box.cy, out_box.cx - p_now.x, out_box.cy - p_now.y, out_box.width, out_box.length,
      out_box.angle_deg;
  return out;
}

StateCovariance transition_jacobian(const StateVector& mean, const Homography& h) {
  StateCovariance jac;
  for (int j = 0; j < kStateSize; ++j) {
    // Steps small against the state's scale but well above rounding of pixel coordinates.
    const double step = (j == kAngle) ? 1e-3 : 1e-4 * std::max(1.0, std::abs(mean(j)));
    StateVector plus = mean;
    StateVector minus = mean;
    plus(j) += step;
    minus(j) -= step;
    const StateVector f_plus = transition(plus, h);
    const StateVector f_minus = transition(minus, h);
    StateVector diff = f_plus - f_minus;
    diff(kAngle) = axis_angle_difference_deg(f_plus(kAngle), f_minus(kAngle));
    jac.col(j) = diff / (2.0 * step);
  }
  return jac;
}

KalmanState predict(const KalmanState& state, const Homography& h, const ProcessNoise& noise) {
  KalmanState out;
  out.mean = transition(state.mean, h);
  const StateCovariance f = transition_jacobian(state.mean, h);
  const StateCovariance q = process_noise_covariance(noise);
  out.covariance = f * state.covariance * f.transpose() + q;
  out.covariance = 0.5 * (out.covariance + out.covariance.transpose());
  return out;
}

}  // namespace uavmot::tracking
