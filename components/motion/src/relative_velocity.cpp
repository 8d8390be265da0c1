#include "relative_velocity.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace uavmot::motion {

void FeatureHistory::carry_forward(const Homography& h) {
  for (auto& p : positions_) p = apply_homography(h, p);
}

void FeatureHistory::push(const cv::Point2f& position, int capacity) {
  if (positions_.capacity() == 0) positions_.reserve(static_cast<size_t>(std::max(1, capacity)) + 1);
  positions_.emplace_back(position.x, position.y);
  const auto excess = static_cast<std::ptrdiff_t>(positions_.size()) - std::max(capacity, 0);
  if (excess > 0) positions_.erase(positions_.begin(), positions_.begin() + excess);
}

VelocityEstimate estimate_velocity(const FeatureHistory& history, const MotionOptions& o) {
  VelocityEstimate out;
  const auto& pos = history.positions();
  const int n = static_cast<int>(pos.size());
  if (n < 2) return out;
  // Time t = 0 .. n-1 (oldest .. current); slope of the least-squares line per axis.
  const double t_mean = (n - 1) / 2.0;
  double mx = 0, my = 0;
  for (const auto& p : pos) {
    mx += p.x;
    my += p.y;
  }
  mx /= n;
  my /= n;
  double stt = 0, stx = 0, sty = 0;
  for (int i = 0; i < n; ++i) {
    const double dt = i - t_mean;
    stt += dt * dt;
    stx += dt * (pos[static_cast<size_t>(i)].x - mx);
    sty += dt * (pos[static_cast<size_t>(i)].y - my);
  }
  out.velocity = {stx / stt, sty / stt};
  // Residual variance per axis (2 dof per axis used by the line), pooled over both axes and
  // shrunk towards the prior tracking noise so a short or lucky track is not over-trusted.
  double rss = 0;
  for (int i = 0; i < n; ++i) {
    const double dt = i - t_mean;
    const double ex = pos[static_cast<size_t>(i)].x - (mx + out.velocity[0] * dt);
    const double ey = pos[static_cast<size_t>(i)].y - (my + out.velocity[1] * dt);
    rss += ex * ex + ey * ey;
  }
  const double dof = 2.0 * std::max(0, n - 2);
  const double prior_var = o.position_sigma_px * o.position_sigma_px;
  const double var = (rss + o.prior_weight * prior_var) / std::max(dof + o.prior_weight, 1e-9);
  out.sigma = std::sqrt(std::max(var, prior_var * 0.25) / stt);
  out.available = true;
  return out;
}

double scene_noise_floor(std::vector<double> speeds, const MotionOptions& o) {
  if (!(o.scene_noise_factor > 0.0) || speeds.size() < 20) return 0.0;
  const auto middle = speeds.begin() + static_cast<long>(speeds.size() / 2);
  std::nth_element(speeds.begin(), middle, speeds.end());
  return std::min(o.scene_noise_factor * *middle / 1.1774, o.scene_noise_max_px);
}

bool MotionClassifier::update(const VelocityEstimate& e, int track_frames, const MotionOptions& o, double floor_px) {
  if (!e.available || track_frames < o.min_track_frames) {
    moving_ = false;
    streak_ = 0;
    return moving_;
  }
  const double speed = std::hypot(e.velocity[0], e.velocity[1]);
  const double threshold = std::max({o.moving_sigma_factor * e.sigma, o.min_moving_speed_px, floor_px});
  const bool argues_for_change = moving_ ? speed < o.release_ratio * threshold : speed > threshold;
  streak_ = argues_for_change ? streak_ + 1 : 0;
  // Only a feature's first decision: a corner that sat still and jumps is a slip or a silhouette.
  const bool strong_start = !moving_ && track_frames == o.min_track_frames && o.strong_motion_factor > 0.0 &&
                            speed > o.strong_motion_factor * threshold;
  if (streak_ >= o.confirm_frames || strong_start) {
    moving_ = !moving_;
    streak_ = 0;
  }
  return moving_;
}

bool is_tracking_slip(const Homography& h, const cv::Point2f& from, const cv::Point2f& to, const VelocityEstimate& known,
                      double max_step_error_px) {
  if (!(max_step_error_px > 0.0) || !known.available) return false;
  const cv::Point2d expected = apply_homography(h, cv::Point2d(from)) + cv::Point2d(known.velocity[0], known.velocity[1]);
  return cv::norm(cv::Point2d(to) - expected) > max_step_error_px;
}

}  // namespace uavmot::motion
