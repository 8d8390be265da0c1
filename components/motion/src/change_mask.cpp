#include "change_mask.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include <opencv2/imgproc.hpp>

namespace uavmot::motion {
namespace {

// Columns [begin, end) of one row.
struct Span {
  int begin = 0, end = 0;
};

// For each row of a `size` image, the columns whose source under `current_to_previous` lies within
// [lo_x, hi_x] x [lo_y, hi_y] of the previous frame. Along a row the source is ((a x + b) / (e x + f),
// (c x + d) / (e x + f)), so each bound (and w = e x + f > 0) is a linear inequality in x: the row's
// valid columns are one interval, found without warping a mask.
std::vector<Span> valid_spans(const Homography& current_to_previous, cv::Size size, double lo_x, double hi_x,
                              double lo_y, double hi_y) {
  const Homography& h = current_to_previous;
  std::vector<Span> spans(static_cast<size_t>(size.height));
  for (int y = 0; y < size.height; ++y) {
    const double a = h(0, 0), b = h(0, 1) * y + h(0, 2);
    const double c = h(1, 0), d = h(1, 1) * y + h(1, 2);
    const double e = h(2, 0), f = h(2, 1) * y + h(2, 2);
    double low = 0.0, high = size.width - 1.0;
    // k x + m >= 0 narrows [low, high] (> 0 when `strict`: only a constant k = 0 tells them apart).
    auto require = [&](double k, double m, bool strict) {
      if (k > 0.0) low = std::max(low, -m / k);
      else if (k < 0.0) high = std::min(high, -m / k);
      else if (m < 0.0 || (strict && m == 0.0)) high = -1.0;
    };
    require(e, f, true);                         // in front of the camera
    require(a - lo_x * e, b - lo_x * f, false);  // x_source >= lo_x
    require(hi_x * e - a, hi_x * f - b, false);  // x_source <= hi_x
    require(c - lo_y * e, d - lo_y * f, false);
    require(hi_y * e - c, hi_y * f - d, false);
    if (!(low <= high)) continue;
    Span& s = spans[static_cast<size_t>(y)];
    s.begin = std::clamp(static_cast<int>(std::ceil(low)), 0, size.width);
    s.end = std::clamp(static_cast<int>(std::floor(high)) + 1, s.begin, size.width);
  }
  return spans;
}

struct Moments {
  double count = 0.0, mean = 0.0, stddev = 0.0;
};

// Rows sampled for the frame's statistics (gain, offset, noise): every kStatsRowStep-th. They are
// a few numbers over a million pixels; a quarter of the rows gives them to well under a grey level.
constexpr int kStatsRowStep = 4;

Moments moments_over(const cv::Mat& image, const std::vector<Span>& spans) {
  int64_t n = 0, sum = 0, sum_sq = 0;  // exact: 2^63 / 255^2 pixels is far beyond any frame
  for (int y = 0; y < image.rows; y += kStatsRowStep) {
    const Span& s = spans[static_cast<size_t>(y)];
    const uchar* row = image.ptr<uchar>(y);
    int64_t row_sum = 0, row_sq = 0;
    for (int x = s.begin; x < s.end; ++x) {
      row_sum += row[x];
      row_sq += row[x] * row[x];
    }
    n += s.end - s.begin;
    sum += row_sum;
    sum_sq += row_sq;
  }
  Moments m;
  if (n == 0) return m;
  m.count = static_cast<double>(n);
  m.mean = static_cast<double>(sum) / m.count;
  m.stddev = std::sqrt(std::max(0.0, static_cast<double>(sum_sq) / m.count - m.mean * m.mean));
  return m;
}

constexpr uchar kCompact = 1, kLong = 2;

}  // namespace

cv::Mat changed_pixels(const cv::Mat& previous, const cv::Mat& current, const Homography& previous_to_current,
                       const MotionOptions& o) {
  if (previous.empty() || current.empty() || previous.size() != current.size()) return {};
  cv::Mat warped;
  cv::warpPerspective(previous, warped, previous_to_current, current.size(), cv::INTER_LINEAR, cv::BORDER_CONSTANT);
  // Pixels whose source is at least half a pixel inside the previous frame (bilinear interpolation
  // at its edge would mix in the border).
  const std::vector<Span> spans = valid_spans(previous_to_current.inv(), current.size(), 0.5, previous.cols - 1.5, 0.5,
                                              previous.rows - 1.5);
  // The sensor's gain and offset drift (auto exposure): matched first, or every high-contrast
  // object, parked cars above all, would differ from frame to frame. One table maps the warped grey.
  const Moments then = moments_over(warped, spans), now = moments_over(current, spans);
  std::array<uchar, 256> matched{};
  const double gain = then.stddev > 1e-6 ? now.stddev / then.stddev : 1.0;
  const double offset = then.stddev > 1e-6 ? now.mean - gain * then.mean : 0.0;
  for (int g = 0; g < 256; ++g) matched[static_cast<size_t>(g)] = cv::saturate_cast<uchar>(gain * g + offset);

  // The noise: the median absolute difference on the sampled rows.
  std::array<int64_t, 256> histogram{};
  int64_t count = 0;
  for (int y = 0; y < current.rows; y += kStatsRowStep) {
    const Span& s = spans[static_cast<size_t>(y)];
    const uchar* c = current.ptr<uchar>(y);
    const uchar* w = warped.ptr<uchar>(y);
    for (int x = s.begin; x < s.end; ++x) {
      const int v = c[x] - matched[w[x]];
      ++histogram[static_cast<size_t>(v < 0 ? -v : v)];
    }
    count += s.end - s.begin;
  }
  // |d| of Gaussian noise has its median at 0.674 sigma: 1.4826 x median is sigma.
  int median = 0;
  for (int64_t seen = 0; median < 255; ++median) {
    seen += histogram[static_cast<size_t>(median)];
    if (2 * seen >= count) break;
  }
  const double threshold = std::max(o.change_min_grey, o.change_threshold_sigma * 1.4826 * median);
  // Changed: |difference| > threshold, i.e. above the largest whole grey level not beyond it.
  const int above = static_cast<int>(std::floor(threshold));
  cv::Mat changed(current.size(), CV_8U, cv::Scalar(0));
  for (int y = 0; y < current.rows; ++y) {
    const Span& s = spans[static_cast<size_t>(y)];
    const uchar* c = current.ptr<uchar>(y);
    const uchar* w = warped.ptr<uchar>(y);
    uchar* m = changed.ptr<uchar>(y);
    for (int x = s.begin; x < s.end; ++x) {
      const int v = c[x] - matched[w[x]];
      m[x] = (v < 0 ? -v : v) > above ? 255 : 0;
    }
  }
  return changed;
}

ChangeBlobs::ChangeBlobs(const cv::Mat& changed, double max_extent_px, int scale)
    : changed_(changed),
      max_extent_(max_extent_px > 0.0 ? static_cast<int>(std::min(std::floor(max_extent_px), 1e9)) : 0),
      scale_(scale) {
  CV_Assert((changed.empty() || changed.type() == CV_8UC1) && scale >= 1);
}

bool ChangeBlobs::compact_at(int full_x, int full_y) {
  if (full_x < 0 || full_y < 0) return false;
  const int x = full_x / scale_, y = full_y / scale_;
  if (x >= changed_.cols || y >= changed_.rows || changed_.at<uchar>(y, x) == 0) return false;
  if (max_extent_ <= 0) return true;
  if (verdict_.empty()) verdict_ = cv::Mat::zeros(changed_.size(), CV_8U);
  if (const uchar v = verdict_.at<uchar>(y, x); v != 0) return v == kCompact;
  // Fill the blob, giving up once its bounding box is longer than max_extent_ or it reaches a
  // pixel already found to be on a long blob.
  const int cols = changed_.cols, rows = changed_.rows;
  stack_.assign(1, y * cols + x);
  visited_.assign(1, y * cols + x);
  verdict_.data[y * cols + x] = kCompact;  // provisional: marks it visited
  int x0 = x, x1 = x, y0 = y, y1 = y;
  bool is_long = false;
  while (!stack_.empty() && !is_long) {
    const int i = stack_.back();
    stack_.pop_back();
    const int px = i % cols, py = i / cols;
    for (int dy = -1; dy <= 1 && !is_long; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        const int nx = px + dx, ny = py + dy;
        if (nx < 0 || ny < 0 || nx >= cols || ny >= rows) continue;
        const int j = ny * cols + nx;
        if (changed_.ptr<uchar>(ny)[nx] == 0) continue;
        const uchar v = verdict_.data[j];
        if (v == kLong) {
          is_long = true;
          break;
        }
        if (v == kCompact) continue;  // this fill's own, or a compact blob (then it is this one)
        verdict_.data[j] = kCompact;
        visited_.push_back(j);
        stack_.push_back(j);
        x0 = std::min(x0, nx), x1 = std::max(x1, nx), y0 = std::min(y0, ny), y1 = std::max(y1, ny);
        if (scale_ * (x1 - x0 + 1) > max_extent_ || scale_ * (y1 - y0 + 1) > max_extent_) {  // in full-size pixels
          is_long = true;
          break;
        }
      }
    }
  }
  if (is_long) {
    for (int j : visited_) verdict_.data[j] = kLong;
  }
  return !is_long;
}

}  // namespace uavmot::motion
