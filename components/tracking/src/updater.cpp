#include "updater.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Cholesky>

namespace uavmot::tracking {
namespace {

template <int M>
KalmanState kalman_update(const KalmanState& state, const Eigen::Matrix<double, M, kStateSize>& h,
                          const Eigen::Matrix<double, M, 1>& innovation, const Eigen::Matrix<double, M, M>& r) {
  const Eigen::Matrix<double, M, M> s = h * state.covariance * h.transpose() + r;
  // K = P H^T S^-1, solved rather than inverted (S is symmetric positive definite).
  const Eigen::Matrix<double, kStateSize, M> pht = state.covariance * h.transpose();
  const Eigen::Matrix<double, kStateSize, M> gain = s.ldlt().solve(pht.transpose()).transpose();
  KalmanState out;
  out.mean = state.mean + gain * innovation;
  // Joseph form keeps the covariance symmetric and positive definite.
  const StateCovariance i_kh = StateCovariance::Identity() - gain * h;
  out.covariance = i_kh * state.covariance * i_kh.transpose() + gain * r * gain.transpose();
  out.covariance = 0.5 * (out.covariance + out.covariance.transpose());
  out.mean(kAngle) = normalize_axis_angle_deg(out.mean(kAngle));
  return out;
}

double labelling_cost(const OrientedBox& m, const OrientedBox& p) {
  const double dw = (m.width - p.width) / std::max(p.width, 1.0);
  const double dl = (m.length - p.length) / std::max(p.length, 1.0);
  const double da = axis_angle_difference_deg(m.angle_deg, p.angle_deg) / 45.0;
  return dw * dw + dl * dl + da * da;
}

}  // namespace

OrientedBox align_box_labelling(const OrientedBox& measured, const OrientedBox& predicted) {
  OrientedBox swapped = measured;
  swapped.width = measured.length;
  swapped.length = measured.width;
  swapped.angle_deg = normalize_axis_angle_deg(measured.angle_deg + 90.0);
  return labelling_cost(swapped, predicted) < labelling_cost(measured, predicted) ? swapped : measured;
}

KalmanState update_with_box(const KalmanState& state, const OrientedBox& measured, const BoxMeasurementNoise& noise,
                            double min_box_size_px) {
  const OrientedBox predicted = box_of(state.mean);
  const OrientedBox z = align_box_labelling(measured, predicted);
  Eigen::Matrix<double, 5, kStateSize> h = Eigen::Matrix<double, 5, kStateSize>::Zero();
  h(0, kX) = h(1, kY) = h(2, kWidth) = h(3, kLength) = h(4, kAngle) = 1.0;
  Eigen::Matrix<double, 5, 1> innovation;
  innovation << z.cx - predicted.cx, z.cy - predicted.cy, z.width - predicted.width, z.length - predicted.length,
      axis_angle_difference_deg(z.angle_deg, predicted.angle_deg);
  // A near-square region says little about the heading.
  const bool ambiguous = std::max(z.length, z.width) < noise.min_elongation_for_angle * std::min(z.length, z.width);
  const double angle_sigma = ambiguous ? noise.ambiguous_angle_sigma_deg : noise.angle_sigma_deg;
  Eigen::Matrix<double, 5, 1> variances;
  variances << noise.position_sigma_px * noise.position_sigma_px, noise.position_sigma_px * noise.position_sigma_px,
      noise.size_sigma_px * noise.size_sigma_px, noise.size_sigma_px * noise.size_sigma_px, angle_sigma * angle_sigma;
  KalmanState out = kalman_update<5>(state, h, innovation, variances.asDiagonal());
  out.mean(kWidth) = std::max(out.mean(kWidth), min_box_size_px);
  out.mean(kLength) = std::max(out.mean(kLength), min_box_size_px);
  return out;
}

void open_size_uncertainty(KalmanState& state, const OrientedBox& measured) {
  const OrientedBox z = align_box_labelling(measured, box_of(state.mean));
  const double dw = z.width - state.mean(kWidth);
  const double dl = z.length - state.mean(kLength);
  state.covariance(kWidth, kWidth) += dw * dw;
  state.covariance(kLength, kLength) += dl * dl;
}

KalmanState update_with_position(const KalmanState& state, const cv::Point2d& centre, double sigma_px) {
  Eigen::Matrix<double, 2, kStateSize> h = Eigen::Matrix<double, 2, kStateSize>::Zero();
  h(0, kX) = h(1, kY) = 1.0;
  Eigen::Matrix<double, 2, 1> innovation(centre.x - state.mean(kX), centre.y - state.mean(kY));
  Eigen::Matrix<double, 2, 2> r = Eigen::Matrix<double, 2, 2>::Identity() * (sigma_px * sigma_px);
  return kalman_update<2>(state, h, innovation, r);
}

OrientedBox box_along_heading(const OrientedBox& region, double heading_deg) {
  // Along and across the heading, the inscribed ellipse's extent understates a tilted blob and the
  // rectangle's corner-to-corner extent overstates it; their mean measured best (docs/tracking.md).
  const double delta = (region.angle_deg - heading_deg) * M_PI / 180.0;
  const double c = std::cos(delta), s = std::sin(delta);
  const double l2 = region.length * region.length, w2 = region.width * region.width;
  const double as = std::abs(s), ac = std::abs(c);
  const double width = 0.5 * (std::sqrt(l2 * s * s + w2 * c * c) + region.length * as + region.width * ac);
  const double length = 0.5 * (std::sqrt(l2 * c * c + w2 * s * s) + region.length * ac + region.width * as);
  return OrientedBox{region.cx, region.cy, width, length, normalize_axis_angle_deg(heading_deg)};
}

OrientedBox lengthen_to_cover(const OrientedBox& box, const std::vector<cv::Point2d>& points, double margin,
                              double max_length) {
  if (box.length >= max_length) return box;
  const double a = box.angle_deg * M_PI / 180.0;
  const double c = std::cos(a), s = std::sin(a);
  double lo = -0.5 * box.length, hi = 0.5 * box.length;
  for (const auto& p : points) {
    const double u = (p.x - box.cx) * c + (p.y - box.cy) * s;
    lo = std::min(lo, u - margin);
    hi = std::max(hi, u + margin);
  }
  // Grow each end in proportion to what it asked for, to max_length at most.
  const double grow = (hi - lo) - box.length;
  if (grow > max_length - box.length) {
    const double keep = (max_length - box.length) / grow;
    lo = -0.5 * box.length + keep * (lo + 0.5 * box.length);
    hi = 0.5 * box.length + keep * (hi - 0.5 * box.length);
  }
  const double shift = 0.5 * (lo + hi);
  return OrientedBox{box.cx + shift * c, box.cy + shift * s, box.width, hi - lo, box.angle_deg};
}

KalmanState update_with_velocity(const KalmanState& state, const cv::Vec2d& velocity, double sigma_px) {
  Eigen::Matrix<double, 2, kStateSize> h = Eigen::Matrix<double, 2, kStateSize>::Zero();
  h(0, kVx) = h(1, kVy) = 1.0;
  Eigen::Matrix<double, 2, 1> innovation(velocity[0] - state.mean(kVx), velocity[1] - state.mean(kVy));
  Eigen::Matrix<double, 2, 2> r = Eigen::Matrix<double, 2, 2>::Identity() * (sigma_px * sigma_px);
  return kalman_update<2>(state, h, innovation, r);
}

namespace {

KalmanState relabel_box(const KalmanState& state) {
  KalmanState out = state;
  // The same box with width and length exchanged and the axis turned by 90 deg: a permutation of the
  // state, so the covariance is permuted alike.
  Eigen::PermutationMatrix<kStateSize> swap;
  swap.setIdentity();
  swap.indices()(kWidth) = kLength;
  swap.indices()(kLength) = kWidth;
  out.mean = swap * state.mean;
  out.covariance = swap * state.covariance * swap.transpose();
  out.mean(kAngle) = normalize_axis_angle_deg(state.mean(kAngle) + 90.0);
  return out;
}

}  // namespace

KalmanState update_with_heading(const KalmanState& state, double heading_deg, double sigma_deg) {
  // A box whose "length" lies across the direction of travel is labelled the wrong way round: relabel
  // it first, or the heading would pull its axis through 90 deg instead of naming the long side.
  const bool across = std::abs(axis_angle_difference_deg(heading_deg, state.mean(kAngle))) > 45.0;
  const KalmanState labelled = across ? relabel_box(state) : state;
  Eigen::Matrix<double, 1, kStateSize> h = Eigen::Matrix<double, 1, kStateSize>::Zero();
  h(0, kAngle) = 1.0;
  Eigen::Matrix<double, 1, 1> innovation(axis_angle_difference_deg(heading_deg, labelled.mean(kAngle)));
  Eigen::Matrix<double, 1, 1> r(sigma_deg * sigma_deg);
  return kalman_update<1>(labelled, h, innovation, r);
}

}  // namespace uavmot::tracking
