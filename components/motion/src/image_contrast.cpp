#include "image_contrast.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace uavmot::motion {

double gradient_percentile(const cv::Mat& gray, double percentile, int row_step) {
  if (gray.type() != CV_8UC1 || gray.rows < 3 || gray.cols < 3) return 0.0;
  // dx, dy: undivided central differences. The histogram is over dx^2 + dy^2 itself (no root per
  // pixel: 0.3 ms instead of 1.1 for a 1080p frame); the root is monotonic, so the percentile's
  // root is the root's percentile.
  constexpr int kMaxSquared = 2 * 255 * 255;
  thread_local std::vector<uint32_t> histogram;
  histogram.assign(kMaxSquared + 1, 0U);
  int64_t count = 0;
  const int step = std::max(1, row_step);
  for (int y = 1; y + 1 < gray.rows; y += step) {
    const uint8_t* up = gray.ptr<uint8_t>(y - 1);
    const uint8_t* row = gray.ptr<uint8_t>(y);
    const uint8_t* down = gray.ptr<uint8_t>(y + 1);
    for (int x = 1; x + 1 < gray.cols; x += 2) {
      const int dx = row[x + 1] - row[x - 1];
      const int dy = down[x] - up[x];
      ++histogram[static_cast<size_t>(dx * dx + dy * dy)];
      ++count;
    }
  }
  if (count == 0) return 0.0;
  const auto rank = std::max<int64_t>(
      1, static_cast<int64_t>(std::ceil(std::clamp(percentile, 0.0, 100.0) / 100.0 * static_cast<double>(count))));
  int64_t seen = 0;
  int squared = 0;
  for (; squared < kMaxSquared; ++squared) {
    seen += histogram[static_cast<size_t>(squared)];
    if (seen >= rank) break;
  }
  // Half-grey-level steps: magnitude sqrt(dx^2 + dy^2) / 2, rounded down to a multiple of 0.5.
  return 0.5 * std::floor(std::sqrt(static_cast<double>(squared)));
}

double corner_response_scale(double contrast, double reference, double min_scale) {
  if (!(reference > 0.0)) return 1.0;
  const double ratio = contrast / reference;
  return std::clamp(ratio * ratio, std::clamp(min_scale, 0.0, 1.0), 1.0);
}

}  // namespace uavmot::motion
