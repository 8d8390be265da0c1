#pragma once
// The virtual camera's smooth trajectory and its ground->image homography.
// World frame: metres on the ground plane, x right, y down (like the image when yaw = 0),
// z into the ground; the camera looks along +z from height h.

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
  // Ground sampling distance at the image centre.
  double gsd_at(double t_s) const;
  double focal_px() const { return focal_px_; }

 private:
  CameraParams params_;
  double focal_px_;
  double phase_yaw_, phase_pitch_, phase_roll_, phase_altitude_;
};

}  // namespace uavmot::sim::detail
