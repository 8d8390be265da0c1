#include "camera_path.hpp"

#include <cmath>
#include <random>

#include <opencv2/core.hpp>

namespace uavmot::sim::detail {
namespace {
constexpr double kPi = 3.14159265358979323846;
double rad(double deg) { return deg * kPi / 180.0; }
}  // namespace

CameraPath::CameraPath(const CameraParams& params, uint64_t seed) : params_(params) {
  focal_px_ = params.altitude_m / params.gsd_m;
  std::mt19937_64 rng(seed ^ 0xCA3E7A11ULL);
  std::uniform_real_distribution<double> phase(0.0, 2.0 * kPi);
  phase_yaw_ = phase(rng);
  phase_pitch_ = phase(rng);
  phase_roll_ = phase(rng);
  phase_altitude_ = phase(rng);
}

CameraPose CameraPath::pose(double t) const {
  CameraPose pose;
  const double heading0 = rad(params_.heading_deg);
  const double omega = rad(params_.path_curvature_dps);
  const double v = params_.speed_mps;
  // Constant speed along a circular arc (a straight line when omega = 0), starting at the origin.
  if (std::abs(omega) < 1e-9) {
    pose.position_m = {v * t * std::cos(heading0), v * t * std::sin(heading0)};
  } else {
    pose.position_m = {v / omega * (std::sin(heading0 + omega * t) - std::sin(heading0)),
                       v / omega * (std::cos(heading0) - std::cos(heading0 + omega * t))};
  }
  const double wobble = 2.0 * kPi / params_.wobble_period_s;
  pose.altitude_m = params_.altitude_m *
                    (1.0 + params_.altitude_change * std::sin(2.0 * kPi * t / params_.altitude_period_s + phase_altitude_));
  pose.yaw_deg = params_.yaw_deg + params_.yaw_rate_dps * t + params_.yaw_wobble_deg * std::sin(wobble * t + phase_yaw_);
  // A positive camera.pitch_deg turns the view forward so the top of the image sees farther.
  pose.pitch_deg = params_.tilt_deg * std::sin(wobble * t + phase_pitch_) - params_.pitch_deg;
  pose.roll_deg = params_.tilt_deg * std::sin(wobble * 0.73 * t + phase_roll_);
  return pose;
}

void CameraPath::extrinsics(double t, cv::Matx33d& rotation, cv::Vec3d& t_vec) const {
  const CameraPose p = pose(t);
  const double cy = std::cos(rad(p.yaw_deg)), sy = std::sin(rad(p.yaw_deg));
  const double cp = std::cos(rad(p.pitch_deg)), sp = std::sin(rad(p.pitch_deg));
  const double cr = std::cos(rad(p.roll_deg)), sr = std::sin(rad(p.roll_deg));
  const cv::Matx33d yaw(cy, sy, 0, -sy, cy, 0, 0, 0, 1);  // world -> camera about the optical axis
  const cv::Matx33d pitch(1, 0, 0, 0, cp, -sp, 0, sp, cp);
  const cv::Matx33d roll(cr, 0, sr, 0, 1, 0, -sr, 0, cr);
  rotation = pitch * roll * yaw;
  const cv::Vec3d centre(p.position_m.x, p.position_m.y, -p.altitude_m);
  t_vec = -(rotation * centre);
}

cv::Matx33d CameraPath::intrinsics() const {
  return cv::Matx33d(focal_px_, 0, (params_.width - 1) / 2.0, 0, focal_px_, (params_.height - 1) / 2.0, 0, 0, 1);
}

cv::Matx33d CameraPath::image_from_world(double t) const {
  cv::Matx33d rotation;
  cv::Vec3d t_vec;
  extrinsics(t, rotation, t_vec);
  const cv::Matx33d plane(rotation(0, 0), rotation(0, 1), t_vec[0],
                          rotation(1, 0), rotation(1, 1), t_vec[1],
                          rotation(2, 0), rotation(2, 1), t_vec[2]);
  cv::Matx33d g = intrinsics() * plane;
  return g * (1.0 / g(2, 2));
}

cv::Matx34d CameraPath::projection(double t) const {
  cv::Matx33d rotation;
  cv::Vec3d t_vec;
  extrinsics(t, rotation, t_vec);
  const cv::Matx34d rt(rotation(0, 0), rotation(0, 1), rotation(0, 2), t_vec[0],
                       rotation(1, 0), rotation(1, 1), rotation(1, 2), t_vec[1],
                       rotation(2, 0), rotation(2, 1), rotation(2, 2), t_vec[2]);
  cv::Matx34d p = intrinsics() * rt;
  return p * (1.0 / std::abs(p(2, 3)));  // positive scale: row 3 stays the depth along the optical axis
}

cv::Point3d CameraPath::centre(double t) const {
  const CameraPose p = pose(t);
  return {p.position_m.x, p.position_m.y, -p.altitude_m};
}

double CameraPath::gsd_at(double t) const { return pose(t).altitude_m / focal_px_; }

}  // namespace uavmot::sim::detail
