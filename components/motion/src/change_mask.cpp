#include "change_mask.hpp"

#include <algorithm>
#include <array>

#include <opencv2/imgproc.hpp>

namespace uavmot::motion {
namespace {

// Median of the CV_8U values of `diff` where `valid` is set, from a histogram (exact, deterministic).
int median_grey(const cv::Mat& diff, const cv::Mat& valid) {
  std::array<int64_t, 256> histogram{};
  int64_t count = 0;
  for (int y = 0; y < diff.rows; ++y) {
    const uchar* d = diff.ptr<uchar>(y);
    const uchar* v = valid.ptr<uchar>(y);
    for (int x = 0; x < diff.cols; ++x) {
      if (!v[x]) continue;
      ++histogram[d[x]];
      ++count;
    }
  }
  int64_t seen = 0;
  for (int g = 0; g < 256; ++g) {
    seen += histogram[static_cast<size_t>(g)];
    if (2 * seen >= count) return g;
  }
  return 0;
}

}  // namespace

cv::Mat changed_pixels(const cv::Mat& previous, const cv::Mat& current, const Homography& previous_to_current,
                       const MotionOptions& o) {
  if (previous.empty() || current.empty() || previous.size() != current.size()) return {};
  cv::Mat warped, valid, diff;
  cv::warpPerspective(previous, warped, previous_to_current, current.size(), cv::INTER_LINEAR, cv::BORDER_CONSTANT);
  // Pixels the previous frame covers, one pixel in from its edge (the interpolation there mixes in the border).
  cv::warpPerspective(cv::Mat(previous.size(), CV_8U, cv::Scalar(255)), valid, previous_to_current, current.size(),
                      cv::INTER_NEAREST, cv::BORDER_CONSTANT);
  cv::erode(valid, valid, cv::Mat());
  // The sensor's gain and offset drift (auto exposure): matched first, or every high-contrast
  // object, parked cars above all, would differ from frame to frame.
  cv::Scalar mean_warped, std_warped, mean_current, std_current;
  cv::meanStdDev(warped, mean_warped, std_warped, valid);
  cv::meanStdDev(current, mean_current, std_current, valid);
  if (std_warped[0] > 1e-6) {
    const double gain = std_current[0] / std_warped[0];
    warped.convertTo(warped, CV_8U, gain, mean_current[0] - gain * mean_warped[0]);
  }
  cv::absdiff(current, warped, diff);
  // |d| of Gaussian noise has its median at 0.674 sigma: 1.4826 x median is sigma.
  const double sigma = 1.4826 * median_grey(diff, valid);
  const double threshold = std::max(o.change_min_grey, o.change_threshold_sigma * sigma);
  cv::Mat changed;
  cv::threshold(diff, changed, threshold, 255, cv::THRESH_BINARY);
  changed &= valid;
  return changed;
}

}  // namespace uavmot::motion
