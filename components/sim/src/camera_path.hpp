#pragma once
// The virtual camera's smooth trajectory and its ground->image homography.
// World frame: metres on the ground plane, x right, y down (like the image when yaw = 0),
// z into the ground; the camera looks along +z from height h (tilted by `pitch_deg` for an
// oblique view). A point at height h above the ground has world z = -h.

#include <cstdint>

#include <opencv2/core/matx.hpp>
#include <opencv2/core/types.hpp>

#include "uavmot/sim/scenario.hpp"

namespace uavmot::sim::detail {

struct CameraPose {
  cv::Point2d position_m;  // ground point below the camera
  double altitude_m = 0.0;
  double yaw_deg = 0.0;
  double pitch_deg = 0.0;
  double roll_deg = 0.0;
};

class CameraPath {
 public:
  CameraPath(const CameraParams& params, uint64_t seed);

  CameraPose pose(double t_s) const;
  // Pinhole projection of the ground plane: world metres -> image px, h33 = 1.
  cv::Matx33d image_from_world(double t_s) const;
  // Full pinhole projection K [R | t] of world points (x, y, z = -height), scaled by a positive
  // factor so that its columns 0, 1, 3 are the ground-plane homography (up to sign) and its last
  // row gives depth along the optical axis.
  cv::Matx34d projection(double t_s) const;
  // Camera centre in world coordinates (z = -altitude).
  cv::Point3d centre(double t_s) const;
  // Ground sampling distance at the image centre.
  double gsd_at(double t_s) const;
  double focal_px() const { return focal_px_; }

 private:
  // World -> camera rotation and translation (x_cam = R x_world + t).
  void extrinsics(double t_s, cv::Matx33d& rotation, cv::Vec3d& translation) const;
  cv::Matx33d intrinsics() const;

  CameraParams params_;
  double focal_px_;
  double phase_yaw_, phase_pitch_, phase_roll_, phase_altitude_;
};

}  // namespace uavmot::sim::detail
