#pragma once
// Reading the previous frame's kept grey windows (ImageCrop) at sub-pixel positions: shared by the
// shift check and the motion evidence, which both compare a region with where its pixels were.

#include <cmath>
#include <cstdint>
#include <vector>

#include <opencv2/core/mat.hpp>
#include <opencv2/core/types.hpp>

#include "uavmot/segmentation/segmenter.hpp"

namespace uavmot::segmentation {

// Whether `p` lies in the window with a pixel to spare to the right and below, as `sample` needs.
inline bool window_holds(const ImageCrop& w, const cv::Point2d& p) {
  return p.x >= w.roi.x && p.y >= w.roi.y && p.x < w.roi.x + w.roi.width - 1 && p.y < w.roi.y + w.roi.height - 1;
}

// Bilinear grey value at `p` (pixel centres at integer coordinates); `p` must be held (window_holds).
inline double sample_window(const ImageCrop& w, const cv::Point2d& p) {
  const double x = p.x - w.roi.x, y = p.y - w.roi.y;
  const int x0 = static_cast<int>(std::floor(x)), y0 = static_cast<int>(std::floor(y));
  const double fx = x - x0, fy = y - y0;
  const uint8_t* r0 = w.pixels.ptr<uint8_t>(y0);
  const uint8_t* r1 = w.pixels.ptr<uint8_t>(y0 + 1);
  return (1 - fy) * ((1 - fx) * r0[x0] + fx * r0[x0 + 1]) + fy * ((1 - fx) * r1[x0] + fx * r1[x0 + 1]);
}

// The previous window that holds most of `area_then` both at rest and moved back by `velocity`
// (the window of the same cluster, usually), or nullptr when none holds any of it.
inline const ImageCrop* window_holding(const std::vector<ImageCrop>& previous, const cv::Rect2d& area_then,
                                       const cv::Point2d& velocity) {
  const cv::Rect2d moved(area_then.tl() - velocity, area_then.size());
  const ImageCrop* source = nullptr;
  double most = 0.0;
  for (const ImageCrop& w : previous) {
    const cv::Rect2d roi(w.roi);
    const double held = std::min((roi & area_then).area(), (roi & moved).area());
    if (held > most) {
      most = held;
      source = &w;
    }
  }
  return source;
}

}  // namespace uavmot::segmentation
