#include "dragged_feature.hpp"

#include <cmath>

#include <opencv2/imgproc.hpp>

namespace uavmot::motion {
namespace {

double rms_difference(const cv::Mat& a, const cv::Mat& b) {
  return cv::norm(a, b, cv::NORM_L2) / std::sqrt(static_cast<double>(a.total()));
}

}  // namespace

bool centre_follows_background(const cv::Mat& previous, const cv::Mat& current, cv::Point2f from, cv::Point2f to,
                               const Homography& current_to_previous, const MotionOptions& options) {
  const cv::Size patch(2 * options.dragged_patch_radius_px + 1, 2 * options.dragged_patch_radius_px + 1);
  const cv::Point2d ground = apply_homography(current_to_previous, cv::Point2d(to));
  cv::Mat here, own, background;
  cv::getRectSubPix(current, patch, to, here, CV_32F);
  cv::getRectSubPix(previous, patch, from, own, CV_32F);
  cv::getRectSubPix(previous, patch, cv::Point2f(static_cast<float>(ground.x), static_cast<float>(ground.y)), background, CV_32F);
  const double own_difference = rms_difference(here, own);
  return own_difference > options.dragged_min_difference &&
         rms_difference(here, background) < options.dragged_ratio * own_difference;
}

double centre_gradient_along(const cv::Mat& image, cv::Point2f at, cv::Vec2d motion, const MotionOptions& options) {
  const double speed = std::hypot(motion[0], motion[1]);
  const int r = options.dragged_patch_radius_px;
  const int cx = cvRound(at.x), cy = cvRound(at.y);
  if (!(speed > 0.0) || cx - r - 1 < 0 || cy - r - 1 < 0 || cx + r + 1 >= image.cols || cy + r + 1 >= image.rows) {
    return 1.0;
  }
  const double ux = motion[0] / speed, uy = motion[1] / speed;
  double along = 0.0, total = 0.0;
  for (int y = cy - r; y <= cy + r; ++y) {
    const uchar* above = image.ptr<uchar>(y - 1);
    const uchar* row = image.ptr<uchar>(y);
    const uchar* below = image.ptr<uchar>(y + 1);
    for (int x = cx - r; x <= cx + r; ++x) {
      const double gx = 0.5 * (row[x + 1] - row[x - 1]), gy = 0.5 * (below[x] - above[x]);
      const double g = gx * ux + gy * uy;
      along += g * g;
      total += gx * gx + gy * gy;
    }
  }
  return total > 0.0 ? along / total : 1.0;
}

}  // namespace uavmot::motion
