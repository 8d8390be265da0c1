#pragma once
// Frame-to-frame homography: a robust first estimate (cv::findHomography with RANSAC or MAGSAC)
// and the sanity checks that decide whether a frame pair is usable.

#include <string>
#include <vector>

#include <opencv2/core/types.hpp>

#include "uavmot/core/homography.hpp"
#include "uavmot/motion/motion_options.hpp"

namespace uavmot::motion {

struct RobustHomography {
  bool ok = false;
  Homography h = Homography::eye();
  std::vector<unsigned char> inliers;  // one flag per correspondence
  int inlier_count = 0;
  std::string failure;  // why !ok, for logs
};

// src (frame k-1) -> dst (frame k). Fails on too few correspondences or inliers, a low inlier
// ratio, or a motion the plausibility checks reject.
RobustHomography estimate_robust_homography(const std::vector<cv::Point2f>& src, const std::vector<cv::Point2f>& dst,
                                            cv::Size image_size, const MotionOptions& options);

// Rejects homographies that are not finite, flip the image, change scale by more than
// max_scale_change or move an image corner by more than max_motion_fraction of the diagonal.
bool plausible_motion(const Homography& h, cv::Size image_size, const MotionOptions& options, std::string* why);

// Root mean square of ||H src - dst|| over the flagged correspondences (px).
double rms_transfer_error(const Homography& h, const std::vector<cv::Point2f>& src,
                          const std::vector<cv::Point2f>& dst, const std::vector<unsigned char>& use);

}  // namespace uavmot::motion
