#include "uavmot/segmentation/gradients.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <mutex>

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

// Sampling of one neighbour: up to four pixels (one when the offset is integral) and weights.
struct Tap {
  int count = 0;
  std::array<int, 4> offset{};
  std::array<float, 4> weight{};
};

// For P <= 16: is_texture_primitive(riu2) of every bit pattern, so a pixel costs one lookup.
std::vector<uint8_t> make_primitive_table(int count) {
  std::vector<uint8_t> table(size_t{1} << count);
  std::array<float, kMaxNeighbours> g{};
  for (size_t mask = 0; mask < table.size(); ++mask) {
    for (int p = 0; p < count; ++p) g[p] = (mask >> p) & 1U ? 1.0f : -1.0f;
    table[mask] = is_texture_primitive(riu2_code(g.data(), count, 0.0f), count) ? 1 : 0;
  }
  return table;
}

// The table of each P, built once per process: a cluster window is a few hundred pixels, and
// building the 256 entries of P = 8 for each of its radii cost about a sixth of its LBP gradient.
constexpr int kMaxTabulatedNeighbours = 16;
const std::vector<uint8_t>& primitive_table(int count) {
  static std::array<std::once_flag, kMaxTabulatedNeighbours + 1> built;
  static std::array<std::vector<uint8_t>, kMaxTabulatedNeighbours + 1> tables;
  const auto i = static_cast<size_t>(count);
  std::call_once(built[i], [&] { tables[i] = make_primitive_table(count); });
  return tables[i];
}

// Adds the LBP gradient of one radius to `acc`; `padded` is the float image with `pad` border.
void add_lbp_radius(const cv::Mat& padded, int pad, int count, double radius, double min_stddev, cv::Mat& acc) {
  const int stride = static_cast<int>(padded.step1());
  std::array<Tap, kMaxNeighbours> taps{};
  for (int p = 0; p < count; ++p) {
    const double angle = 2.0 * kPi * p / count;
    double dx = radius * std::cos(angle), dy = -radius * std::sin(angle);
    if (std::abs(dx - std::round(dx)) < 1e-9) dx = std::round(dx);
    if (std::abs(dy - std::round(dy)) < 1e-9) dy = std::round(dy);
    const int x0 = static_cast<int>(std::floor(dx)), y0 = static_cast<int>(std::floor(dy));
    const double fx = dx - x0, fy = dy - y0;
    const std::array<int, 4> offsets = {y0 * stride + x0, y0 * stride + x0 + 1, (y0 + 1) * stride + x0,
                                        (y0 + 1) * stride + x0 + 1};
    const std::array<double, 4> weights = {(1 - fx) * (1 - fy), fx * (1 - fy), (1 - fx) * fy, fx * fy};
    for (int i = 0; i < 4; ++i) {
      if (weights[i] == 0.0) continue;
      taps[p].offset[taps[p].count] = offsets[i];
      taps[p].weight[taps[p].count] = static_cast<float>(weights[i]);
      ++taps[p].count;
    }
  }
  static const std::vector<uint8_t> kNoTable;
  const std::vector<uint8_t>& table = count <= kMaxTabulatedNeighbours ? primitive_table(count) : kNoTable;

  const float min_variance = static_cast<float>(min_stddev * min_stddev);
  const float inv_count = 1.0f / static_cast<float>(count);
  const int width = acc.cols;
  // Row at a time, neighbour by neighbour, so the inner loops run over x and vectorise.
  std::vector<float> samples(static_cast<size_t>(count) * width), sum(width), sum_sq(width);
  std::vector<uint32_t> brighter(width), darker(width);
  std::array<float, kMaxNeighbours> g{};
  for (int y = 0; y < acc.rows; ++y) {
    const float* centre = padded.ptr<float>(y + pad) + pad;
    std::fill(sum.begin(), sum.end(), 0.0f);
    std::fill(sum_sq.begin(), sum_sq.end(), 0.0f);
    std::fill(brighter.begin(), brighter.end(), 0U);
    std::fill(darker.begin(), darker.end(), 0U);
    for (int p = 0; p < count; ++p) {
      const Tap& t = taps[p];
      float* v = samples.data() + static_cast<size_t>(p) * width;
      const float* src0 = centre + t.offset[0];
      for (int x = 0; x < width; ++x) v[x] = t.weight[0] * src0[x];
      for (int i = 1; i < t.count; ++i) {
        const float* src = centre + t.offset[i];
        const float w = t.weight[i];
        for (int x = 0; x < width; ++x) v[x] += w * src[x];
      }
      const uint32_t bit = 1U << p;
      for (int x = 0; x < width; ++x) {
        sum[x] += v[x];
        sum_sq[x] += v[x] * v[x];
        brighter[x] |= v[x] - centre[x] >= -kBitTolerance ? bit : 0U;
        darker[x] |= centre[x] - v[x] >= -kBitTolerance ? bit : 0U;
      }
    }
    float* out = acc.ptr<float>(y);
    for (int x = 0; x < width; ++x) {
      const float mean = sum[x] * inv_count;
      const float variance = std::max(0.0f, sum_sq[x] * inv_count - mean * mean);
      if (variance < min_variance || variance <= 0.0f) continue;
      // Ojala's s(x) = [x >= 0] files the darker side of a step with the flat patterns (all
      // neighbours >= centre); the negative image's pattern catches that side.
      bool primitive = false;
      if (!table.empty()) {
        primitive = table[brighter[x]] != 0 || table[darker[x]] != 0;
      } else {
        for (int p = 0; p < count; ++p) g[p] = samples[static_cast<size_t>(p) * width + x];
        primitive = is_texture_primitive(riu2_code(g.data(), count, centre[x]), count) ||
                    is_texture_primitive(riu2_code(g.data(), count, centre[x], -1.0f), count);
      }
      if (primitive) out[x] += std::sqrt(variance);
    }
  }
}

// `gray` as float with a replicated border of `pad` pixels.
cv::Mat padded_float(const cv::Mat& gray, int pad) {
  cv::Mat padded8, padded;
  cv::copyMakeBorder(gray, padded8, pad, pad, pad, pad, cv::BORDER_REPLICATE);
  padded8.convertTo(padded, CV_32F);
  return padded;
}

// dst(y, x) = sum_k kernel[k] * src(y, x + k) over the columns dst needs (horizontal pass), or
// the same along rows (vertical pass). src has `extra` more columns (rows) than dst.
void correlate_rows(const cv::Mat& src, const std::vector<float>& kernel, int x_offset, cv::Mat& dst) {
  const int taps = static_cast<int>(kernel.size());
  for (int y = 0; y < dst.rows; ++y) {
    const float* in = src.ptr<float>(y) + x_offset;
    float* out = dst.ptr<float>(y);
    for (int x = 0; x < dst.cols; ++x) out[x] = 0.0f;
    for (int k = 0; k < taps; ++k) {
      const float w = kernel[k];
      if (w == 0.0f) continue;
      for (int x = 0; x < dst.cols; ++x) out[x] += w * in[x + k];
    }
  }
}

void correlate_columns(const cv::Mat& src, const std::vector<float>& kernel, int y_offset, cv::Mat& dst) {
  const int taps = static_cast<int>(kernel.size());
  for (int y = 0; y < dst.rows; ++y) {
    float* out = dst.ptr<float>(y);
    for (int x = 0; x < dst.cols; ++x) out[x] = 0.0f;
    for (int k = 0; k < taps; ++k) {
      const float w = kernel[k];
      if (w == 0.0f) continue;
      const float* in = src.ptr<float>(y + y_offset + k);
      for (int x = 0; x < dst.cols; ++x) out[x] += w * in[x];
    }
  }
}

std::vector<float> as_vector(const cv::Mat& kernel) { return std::vector<float>(kernel.begin<float>(), kernel.end<float>()); }

// Separable max (dilate) or min (erode) over a size x size square, borders replicated.
template <bool kMaximum>
void square_extremum(const cv::Mat& padded, int pad, int size, cv::Mat& rows_buffer, cv::Mat& dst) {
  const auto pick = [](uchar a, uchar b) { return kMaximum ? std::max(a, b) : std::min(a, b); };
  const int h = size / 2;
  const int width = dst.cols, height = dst.rows;
  rows_buffer.create(height + 2 * h, width, CV_8U);
  for (int y = 0; y < height + 2 * h; ++y) {
    const uchar* in = padded.ptr<uchar>(y + pad - h) + pad - h;
    uchar* out = rows_buffer.ptr<uchar>(y);
    for (int x = 0; x < width; ++x) out[x] = in[x];
    for (int k = 1; k < size; ++k) {
      for (int x = 0; x < width; ++x) out[x] = pick(out[x], in[x + k]);
    }
  }
  for (int y = 0; y < height; ++y) {
    uchar* out = dst.ptr<uchar>(y);
    const uchar* first = rows_buffer.ptr<uchar>(y);
    for (int x = 0; x < width; ++x) out[x] = first[x];
    for (int k = 1; k < size; ++k) {
      const uchar* in = rows_buffer.ptr<uchar>(y + k);
      for (int x = 0; x < width; ++x) out[x] = pick(out[x], in[x]);
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
  int pad = 0;
  for (double sigma : sigmas_px) pad = std::max(pad, kernel_radius(sigma));
  const cv::Mat padded = padded_float(gray, pad);
  cv::Mat derivative_rows(padded.rows, gray.cols, CV_32F), smooth_rows(padded.rows, gray.cols, CV_32F);
  cv::Mat gx(gray.size(), CV_32F), gy(gray.size(), CV_32F);
  for (double sigma : sigmas_px) {
    const std::vector<float> d = as_vector(korn_derivative_kernel(sigma)), s = as_vector(korn_smoothing_kernel(sigma));
    const int offset = pad - kernel_radius(sigma);
    // Separable: x-derivative = rows with d, then columns with s; y-derivative the other way.
    correlate_rows(padded, d, offset, derivative_rows);
    correlate_rows(padded, s, offset, smooth_rows);
    correlate_columns(derivative_rows, s, offset, gx);
    correlate_columns(smooth_rows, d, offset, gy);
    for (int y = 0; y < acc.rows; ++y) {
      const float* a = gx.ptr<float>(y);
      const float* b = gy.ptr<float>(y);
      float* out = acc.ptr<float>(y);
      for (int x = 0; x < acc.cols; ++x) out[x] += std::sqrt(a[x] * a[x] + b[x] * b[x]);
    }
  }
  return acc;
}

cv::Mat morphological_gradient(const cv::Mat& gray, const std::vector<int>& sizes_px) {
  require_gray(gray, "morphological_gradient");
  cv::Mat acc = cv::Mat::zeros(gray.size(), CV_32F);
  if (gray.empty()) return acc;
  int pad = 0;
  for (int size : sizes_px) pad = std::max(pad, size / 2);
  cv::Mat padded;
  // Replicating the border leaves the max/min over a clipped neighbourhood unchanged.
  cv::copyMakeBorder(gray, padded, pad, pad, pad, pad, cv::BORDER_REPLICATE);
  cv::Mat buffer, dilated(gray.size(), CV_8U), eroded(gray.size(), CV_8U);
  for (int size : sizes_px) {
    square_extremum<true>(padded, pad, size, buffer, dilated);
    square_extremum<false>(padded, pad, size, buffer, eroded);
    for (int y = 0; y < acc.rows; ++y) {
      const uchar* a = dilated.ptr<uchar>(y);
      const uchar* b = eroded.ptr<uchar>(y);
      float* out = acc.ptr<float>(y);
      for (int x = 0; x < acc.cols; ++x) out[x] += static_cast<float>(a[x] - b[x]);
    }
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
  int pad = 0;
  for (double radius : radii_px) pad = std::max(pad, static_cast<int>(std::ceil(radius)) + 1);
  const cv::Mat padded = padded_float(gray, pad);
  for (double radius : radii_px) add_lbp_radius(padded, pad, neighbours, radius, min_stddev, acc);
  return acc;
}

}  // namespace uavmot::segmentation
