#pragma once
// Whether a point lies in the image. Pixel centres are at integer coordinates (docs/conventions.md),
// so a width x height image covers [-0.5, width - 0.5) x [-0.5, height - 0.5).

#include <opencv2/core/types.hpp>

namespace uavmot {

inline bool inside_image(const cv::Point2d& p, const cv::Size& image) {
  return p.x >= -0.5 && p.y >= -0.5 && p.x < image.width - 0.5 && p.y < image.height - 0.5;
}

}  // namespace uavmot
