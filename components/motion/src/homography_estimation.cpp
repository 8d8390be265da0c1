#include "homography_estimation.hpp"

#include <cmath>

#include <opencv2/calib3d.hpp>

namespace uavmot::motion {

bool plausible_motion(const Homography& h, cv::Size size, const MotionOptions& o, std::string* why) {
  auto fail = [why](const std::string& reason) {
    if (why) *why = reason;
    return false;
  };
  if (!is_finite(h) || std::abs(h(2, 2)) < 1e-12) return fail("homography not finite");
  const cv::Point2d centre((size.width - 1) / 2.0, (size.height - 1) / 2.0);
  const cv::Matx22d jac = homography_jacobian(h, centre);
  const double det = cv::determinant(jac);
  if (!(det > 0.0)) return fail("homography flips the image");
  if (std::abs(std::sqrt(det) - 1.0) > o.max_scale_change) return fail("scale change too large");
  const double limit = o.max_motion_fraction * std::hypot(size.width, size.height);
  const double w = size.width - 1.0, hgt = size.height - 1.0;
  for (const cv::Point2d corner : {cv::Point2d(0, 0), cv::Point2d(w, 0), cv::Point2d(0, hgt), cv::Point2d(w, hgt)}) {
    const cv::Point2d moved = apply_homography(h, corner);
    if (!std::isfinite(moved.x) || !std::isfinite(moved.y) || cv::norm(moved - corner) > limit) {
      return fail("motion too large");
    }
  }
  return true;
}

double rms_transfer_error(const Homography& h, const std::vector<cv::Point2f>& src, const std::vector<cv::Point2f>& dst,
                          const std::vector<unsigned char>& use) {
  double sum = 0.0;
  size_t n = 0;
  for (size_t i = 0; i < src.size(); ++i) {
    if (!use[i]) continue;
    const cv::Point2d d = apply_homography(h, cv::Point2d(src[i])) - cv::Point2d(dst[i]);
    sum += d.dot(d);
    ++n;
  }
  return n ? std::sqrt(sum / static_cast<double>(n)) : 0.0;
}

RobustHomography estimate_robust_homography(const std::vector<cv::Point2f>& src, const std::vector<cv::Point2f>& dst,
                                            cv::Size size, const MotionOptions& o) {
  RobustHomography out;
  if (static_cast<int>(src.size()) < o.min_inliers) {
    out.failure = "too few tracked features (" + std::to_string(src.size()) + ")";
    return out;
  }
  const int method = o.robust_method == "magsac" ? cv::USAC_MAGSAC : cv::RANSAC;
  cv::Mat mask;
  cv::Mat h = cv::findHomography(src, dst, method, o.ransac_threshold_px, mask, o.ransac_max_iterations,
                                 o.ransac_confidence);
  if (h.empty() || mask.empty()) {
    out.failure = "no homography found";
    return out;
  }
  out.inliers.assign(mask.begin<unsigned char>(), mask.end<unsigned char>());
  for (auto& flag : out.inliers) flag = flag ? 1 : 0;
  out.inlier_count = cv::countNonZero(mask);
  Homography candidate(h.ptr<double>());
  if (!normalize_homography(candidate)) {
    out.failure = "homography not finite";
    return out;
  }
  out.h = candidate;
  if (out.inlier_count < o.min_inliers) {
    out.failure = "too few inliers (" + std::to_string(out.inlier_count) + ")";
    return out;
  }
  if (out.inlier_count < o.min_inlier_ratio * static_cast<double>(src.size())) {
    out.failure = "inlier ratio too low (" + std::to_string(out.inlier_count) + "/" + std::to_string(src.size()) + ")";
    return out;
  }
  if (!plausible_motion(candidate, size, o, &out.failure)) return out;
  out.ok = true;
  return out;
}

}  // namespace uavmot::motion
