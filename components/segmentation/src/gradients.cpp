#include "uavmot/segmentation/gradients.hpp"

#include <array>
#include <cmath>

#include <opencv2/imgproc.hpp>

#include "uavmot/core/error.hpp"

namespace uavmot::segmentation {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kMaxNeighbours = 32;
// Interpolated neighbours of a flat patch differ from the centre by float rounding only;
// Ojala's s(x) = [x >= 0] is applied with this tolerance so flat stays flat (pattern P).
constexpr float kBitTolerance = 1e-3f;

void require_gray(const cv::Mat& gray, const char* who) {
  if (gray.type() != CV_8UC1) throw InvalidArgument(std::string(who) + ": expected a CV_8UC1 image");
}

int kernel_radius(double sigma) { return std::max(1, static_cast<int>(std::ceil(3.0 * sigma))); }

// riu2 code of one pixel from its P sampled neighbours; sign = -1 codes the negative image.
inline int riu2_code(const float* g, int count, float centre, float sign = 1.0f) {
  int ones = 0, transitions = 0;
  bool previous = sign * (g[count - 1] - centre) >= -kBitTolerance;
  for (int p = 0; p < count; ++p) {
    const bool bit = sign * (g[p] - centre) >= -kBitTolerance;
    ones += bit ? 1 : 0;
    transitions += bit != previous ? 1 : 0;
    previous = bit;
  }
  return transitions <= 2 ? ones : count + 1;
}

// Adds the LBP gradient of one radius to `acc`.
void add_lbp_radius(const cv::Mat& gray, int count, double radius, double min_stddev, cv::Mat& acc) {
  const int pad = static_cast<int>(std::ceil(radius)) + 1;
  cv::Mat padded8, padded;
  cv::copyMakeBorder(gray, padded8, pad, pad, pad, pad, cv::BORDER_REPLICATE);
  padded8.convertTo(padded, CV_32F);
  const int stride = static_cast<int>(padded.step1());

  // Bilinear sampling of each neighbour: four pixel offsets and weights, the same for every pixel.
  std::array<std::array<int, 4>, kMaxNeighbours> offsets{};
  std::array<std::array<float, 4>, kMaxNeighbours> weights{};
  for (int p = 0; p < count; ++p) {
    const double angle = 2.0 * kPi * p / count;
    double dx = radius * std::cos(angle), dy = -radius * std::sin(angle);
    if (std::abs(dx - std::round(dx)) < 1e-9) dx = std::round(dx);
    if (std::abs(dy - std::round(dy)) < 1e-9) dy = std::round(dy);
    const int x0 = static_cast<int>(std::floor(dx)), y0 = static_cast<int>(std::floor(dy));
    const double fx = dx - x0, fy = dy - y0;
    offsets[p] = {y0 * stride + x0, y0 * stride + x0 + 1, (y0 + 1) * stride + x0, (y0 + 1) * stride + x0 + 1};
    weights[p] = {static_cast<float>((1 - fx) * (1 - fy)), static_cast<float>(fx * (1 - fy)),
                  static_cast<float>((1 - fx) * fy), static_cast<float>(fx * fy)};
  }

  const float min_variance = static_cast<float>(min_stddev * min_stddev);
  const float inv_count = 1.0f / static_cast<float>(count);
  std::array<float, kMaxNeighbours> g{};
  for (int y = 0; y < gray.rows; ++y) {
    const float* row = padded.ptr<float>(y + pad) + pad;
    float* out = acc.ptr<float>(y);
    for (int x = 0; x < gray.cols; ++x) {
      const float* c = row + x;
      float sum = 0.0f, sum_sq = 0.0f;
      for (int p = 0; p < count; ++p) {
        const auto& o = offsets[p];
        const auto& w = weights[p];
        const float v = w[0] * c[o[0]] + w[1] * c[o[1]] + w[2] * c[o[2]] + w[3] * c[o[3]];
        g[p] = v;
        sum += v;
        sum_sq += v * v;
      }
      const float mean = sum * inv_count;
      const float variance = std::max(0.0f, sum_sq * inv_count - mean * mean);
      if (variance < min_variance || variance <= 0.0f) continue;
      // Ojala's s(x) = [x >= 0] files the darker side of a step with the flat patterns (all
      // neighbours >= centre); the negative image's pattern catches that side.
      if (!is_texture_primitive(riu2_code(g.data(), count, *c), count) &&
          !is_texture_primitive(riu2_code(g.data(), count, *c, -1.0f), count)) {
        continue;
      }
      out[x] += std::sqrt(variance);
    }
  }
}

}  // namespace

cv::Mat korn_derivative_kernel(double sigma_px) {
  const int r = kernel_radius(sigma_px);
  cv::Mat k(2 * r + 1, 1, CV_32F);
  double positive_sum = 0.0;
  std::vector<double> values(2 * r + 1);
  for (int x = -r; x <= r; ++x) {
    values[x + r] = x * std::exp(-0.5 * x * x / (sigma_px * sigma_px));
    if (x > 0) positive_sum += values[x + r];
  }
  for (int i = 0; i < 2 * r + 1; ++i) k.at<float>(i) = static_cast<float>(values[i] / positive_sum);
  return k;
}

cv::Mat korn_smoothing_kernel(double sigma_px) {
  const int r = kernel_radius(sigma_px);
  cv::Mat k(2 * r + 1, 1, CV_32F);
  double sum = 0.0;
  std::vector<double> values(2 * r + 1);
  for (int x = -r; x <= r; ++x) sum += values[x + r] = std::exp(-0.5 * x * x / (sigma_px * sigma_px));
  for (int i = 0; i < 2 * r + 1; ++i) k.at<float>(i) = static_cast<float>(values[i] / sum);
  return k;
}

cv::Mat korn_gradient(const cv::Mat& gray, const std::vector<double>& sigmas_px) {
  require_gray(gray, "korn_gradient");
  cv::Mat acc = cv::Mat::zeros(gray.size(), CV_32F);
  if (gray.empty()) return acc;
  cv::Mat gx, gy, magnitude;
  for (double sigma : sigmas_px) {
    const cv::Mat d = korn_derivative_kernel(sigma), s = korn_smoothing_kernel(sigma);
    cv::sepFilter2D(gray, gx, CV_32F, d, s, cv::Point(-1, -1), 0.0, cv::BORDER_REPLICATE);
    cv::sepFilter2D(gray, gy, CV_32F, s, d, cv::Point(-1, -1), 0.0, cv::BORDER_REPLICATE);
    cv::magnitude(gx, gy, magnitude);
    acc += magnitude;
  }
  return acc;
}

cv::Mat morphological_gradient(const cv::Mat& gray, const std::vector<int>& sizes_px) {
  require_gray(gray, "morphological_gradient");
  cv::Mat acc = cv::Mat::zeros(gray.size(), CV_32F);
  if (gray.empty()) return acc;
  cv::Mat dilated, eroded, difference;
  for (int size : sizes_px) {
    const cv::Mat element = cv::getStructuringElement(cv::MORPH_RECT, cv::Size(size, size));
    // Default borders ignore outside pixels, the same as replicating the border for max/min.
    cv::dilate(gray, dilated, element);
    cv::erode(gray, eroded, element);
    cv::subtract(dilated, eroded, difference);  // dilate >= erode, no saturation
    cv::accumulate(difference, acc);
  }
  return acc;
}

int lbp_riu2(double centre, const std::vector<double>& neighbours) {
  if (neighbours.empty() || neighbours.size() > kMaxNeighbours) throw InvalidArgument("lbp_riu2: 1..32 neighbours");
  std::array<float, kMaxNeighbours> g{};
  for (size_t i = 0; i < neighbours.size(); ++i) g[i] = static_cast<float>(neighbours[i]);
  return riu2_code(g.data(), static_cast<int>(neighbours.size()), static_cast<float>(centre));
}

cv::Mat lbp_gradient(const cv::Mat& gray, int neighbours, const std::vector<double>& radii_px, double min_stddev) {
  require_gray(gray, "lbp_gradient");
  if (neighbours < 4 || neighbours > kMaxNeighbours) throw InvalidArgument("lbp_gradient: neighbours must be in [4, 32]");
  cv::Mat acc = cv::Mat::zeros(gray.size(), CV_32F);
  if (gray.empty()) return acc;
  for (double radius : radii_px) add_lbp_radius(gray, neighbours, radius, min_stddev, acc);
  return acc;
}

}  // namespace uavmot::segmentation
