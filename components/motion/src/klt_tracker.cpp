#include "klt_tracker.hpp"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>

#include "active_picture.hpp"

namespace uavmot::motion {

void build_pyramid(const cv::Mat& gray, const MotionOptions& o, Pyramid& pyramid) {
  pyramid.size = gray.size();
  pyramid.picture = active_picture_area(gray, o);
  // Copies into a bordered buffer (tryReuseInputImage = false): the caller's frame buffer may be reused.
  // OpenCV refills levels that already have the right size in place, so a reused pyramid costs no
  // allocation (about 13 MB per 1080p frame, whose page faults were a visible share of the time).
  cv::buildOpticalFlowPyramid(gray, pyramid.levels, cv::Size(o.lk_window_px, o.lk_window_px), o.pyramid_levels,
                              /*withDerivatives=*/true, cv::BORDER_REFLECT_101, cv::BORDER_CONSTANT,
                              /*tryReuseInputImage=*/false);
}

// LK's minimum eigenvalue (OPTFLOW_LK_GET_MIN_EIGENVALS) is the window's mean squared gradient
// (grey levels per pixel) / 1 024, cv::cornerMinEigenVal's the 5 x 5 block's sum of it / 406 406,
// i.e. its mean / 16 256: about 16 to one where the texture is uniform. At a corner just detected,
// whose 5 x 5 block is the strongest part of the 11 x 11 window, LK's value is lower (a median 9 to
// one on `paper` frame 10), so a feature starts at about half its detection response.
constexpr float kLkEigenPerCornerResponse = 16.0f;

void track_features(const Pyramid& previous, const Pyramid& current, const std::vector<cv::Point2f>& from,
                    const std::vector<cv::Point2f>& guess, int levels, const MotionOptions& o, std::vector<cv::Point2f>& to,
                    std::vector<unsigned char>& tracked, std::vector<float>& corner_strength) {
  tracked.assign(from.size(), 0);
  corner_strength.assign(from.size(), 0.0f);
  to = guess;
  if (from.empty()) return;
  const cv::Size window(o.lk_window_px, o.lk_window_px);
  const cv::TermCriteria criteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, o.lk_max_iterations,
                                  o.lk_epsilon_px);
  std::vector<unsigned char> forward_ok, backward_ok;
  std::vector<float> error;
  std::vector<float> min_eigen;  // of each window in `previous` at full resolution; the flag changes nothing else
  cv::calcOpticalFlowPyrLK(previous.levels, current.levels, from, to, forward_ok, min_eigen, window, levels,
                           criteria, cv::OPTFLOW_USE_INITIAL_FLOW | cv::OPTFLOW_LK_GET_MIN_EIGENVALS);
  // Backward from the answer, starting at the original position: a consistent track needs no
  // coarse levels to come back, so this costs a fraction of the forward pass.
  std::vector<cv::Point2f> back = from;
  cv::calcOpticalFlowPyrLK(current.levels, previous.levels, to, back, backward_ok, error, window, o.backward_levels,
                           criteria, cv::OPTFLOW_USE_INITIAL_FLOW);
  const float max_fb2 = static_cast<float>(o.max_forward_backward_px * o.max_forward_backward_px);
  const cv::Rect usable = usable_area(current.picture, o.border_px);
  const float lo_x = static_cast<float>(usable.x), lo_y = static_cast<float>(usable.y);
  const float hi_x = static_cast<float>(usable.br().x - 1), hi_y = static_cast<float>(usable.br().y - 1);
  for (size_t i = 0; i < from.size(); ++i) {
    if (!forward_ok[i] || !backward_ok[i]) continue;
    const cv::Point2f d = back[i] - from[i];
    if (!(d.x * d.x + d.y * d.y <= max_fb2)) continue;  // also rejects NaN
    const cv::Point2f& p = to[i];
    if (!(p.x >= lo_x && p.y >= lo_y && p.x <= hi_x && p.y <= hi_y)) continue;
    tracked[i] = 1;
    corner_strength[i] = min_eigen[i] / kLkEigenPerCornerResponse;
  }
}

cv::Point2d coarse_translation(const Pyramid& previous, const Pyramid& current, bool& confident) {
  confident = false;
  // buildOpticalFlowPyramid with derivatives interleaves image and derivative levels.
  const int levels = static_cast<int>(previous.levels.size()) / 2;
  int level = 0;
  while (level + 1 < levels && std::min(previous.levels[static_cast<size_t>(2 * (level + 1))].cols,
                                        previous.levels[static_cast<size_t>(2 * (level + 1))].rows) >= 64) {
    ++level;
  }
  if (level >= static_cast<int>(current.levels.size()) / 2) return {0, 0};
  cv::Mat a, b, window;
  previous.levels[static_cast<size_t>(2 * level)].convertTo(a, CV_32F);
  current.levels[static_cast<size_t>(2 * level)].convertTo(b, CV_32F);
  if (a.size() != b.size() || a.empty()) return {0, 0};
  cv::createHanningWindow(window, a.size(), CV_32F);
  double response = 0.0;
  const cv::Point2d shift = cv::phaseCorrelate(a, b, window, &response);
  confident = response > 0.02 && std::isfinite(shift.x) && std::isfinite(shift.y);
  return shift * static_cast<double>(1 << level);
}

}  // namespace uavmot::motion
