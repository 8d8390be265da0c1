#include "dragged_feature.hpp"

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

}  // namespace uavmot::motion
