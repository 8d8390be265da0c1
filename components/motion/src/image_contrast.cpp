#include "image_contrast.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

namespace uavmot::motion {

double gradient_percentile(const cv::Mat& gray, double percentile, int row_step) {
  if (gray.type() != CV_8UC1 || gray.rows < 3 || gray.cols < 3) return 0.0;
  // dx, dy: undivided central differences, so dx^2 + dy^2 <= 2 x 255^2 and its root < 361 bins.
  constexpr int kBins = 512;
  std::array<int64_t, kBins> histogram{};
  int64_t count = 0;
  const int step = std::max(1, row_step);
  for (int y = 1; y + 1 < gray.rows; y += step) {
    const uint8_t* up = gray.ptr<uint8_t>(y - 1);
    const uint8_t* row = gray.ptr<uint8_t>(y);
    const uint8_t* down = gray.ptr<uint8_t>(y + 1);
    for (int x = 1; x + 1 < gray.cols; x += 2) {
      const int dx = row[x + 1] - row[x - 1];
      const int dy = down[x] - up[x];
      // Bin b holds magnitudes (sqrt(dx^2 + dy^2) / 2) in [b / 2, (b + 1) / 2). A float root is exact
      // enough: below 2^24 no integer's root rounds up to the next whole number.
      const int bin = std::min(kBins - 1, static_cast<int>(std::sqrt(static_cast<float>(dx * dx + dy * dy))));
      ++histogram[static_cast<size_t>(bin)];
      ++count;
    }
  }
  if (count == 0) return 0.0;
  const auto rank = static_cast<int64_t>(std::ceil(std::clamp(percentile, 0.0, 100.0) / 100.0 * static_cast<double>(count)));
  int64_t seen = 0;
  for (int bin = 0; bin < kBins; ++bin) {
    seen += histogram[static_cast<size_t>(bin)];
    if (seen >= std::max<int64_t>(1, rank)) return 0.5 * bin;
  }
  return 0.5 * (kBins - 1);
}

double corner_response_scale(double contrast, double reference, double min_scale) {
  if (!(reference > 0.0)) return 1.0;
  const double ratio = contrast / reference;
  return std::clamp(ratio * ratio, std::clamp(min_scale, 0.0, 1.0), 1.0);
}

}  // namespace uavmot::motion
