#include "uavmot/segmentation/blob_regions.hpp"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

#include "uavmot/core/error.hpp"

namespace uavmot::segmentation {
namespace {

// The rectangle with the same area moments as the filled mask: a uniformly filled L x W
// rectangle has variance L^2 / 12 along its length; sampling it on the pixel grid adds each
// pixel's own 1/12 in every direction, which is removed, so rotated shapes are not inflated.
cv::RotatedRect moment_box(const cv::Mat& mask) {
  const cv::Moments m = cv::moments(mask, true);
  if (m.m00 <= 0.0) return {};
  const double cx = m.m10 / m.m00, cy = m.m01 / m.m00;
  const double a = m.mu20 / m.m00, b = m.mu11 / m.m00, c = m.mu02 / m.m00;
  const double mean = 0.5 * (a + c), diff = std::sqrt(0.25 * (a - c) * (a - c) + b * b);
  const double major = mean + diff, minor = std::max(0.0, mean - diff);
  const double angle = 0.5 * std::atan2(2.0 * b, a - c) * 180.0 / 3.14159265358979323846;
  const auto side = [](double variance) { return static_cast<float>(std::sqrt(std::max(0.0, 12.0 * variance + 1.0))); };
  return cv::RotatedRect(cv::Point2f(static_cast<float>(cx), static_cast<float>(cy)), cv::Size2f(side(major), side(minor)),
                         static_cast<float>(angle));
}

}  // namespace

cv::Mat normalise_accumulator(const cv::Mat& acc, double reference_max) {
  double max_value = 0.0;
  if (!acc.empty()) cv::minMaxLoc(acc, nullptr, &max_value);
  const double scale = 255.0 / std::max({max_value, reference_max, 1e-12});
  cv::Mat out;
  acc.convertTo(out, CV_32F, scale);
  return out;
}

cv::Mat fuse_accumulators(const std::vector<cv::Mat>& normalised, FusionRule rule) {
  if (normalised.empty()) throw InvalidArgument("fuse_accumulators: no accumulators");
  cv::Mat fused = normalised.front().clone();
  if (normalised.size() == 1) return fused;
  if (rule == FusionRule::Sum) {
    for (size_t i = 1; i < normalised.size(); ++i) fused += normalised[i];
  } else {
    for (size_t i = 1; i < normalised.size(); ++i) cv::multiply(fused, normalised[i], fused, 1.0 / 255.0);
  }
  return fused;
}

double adaptive_threshold(const cv::Mat& acc, double quantile, double min_value) {
  if (acc.empty()) return min_value;
  // Quantile from a fine histogram over [0, max]: linear time, and exact to 1/4096 of the range.
  constexpr int kBins = 4096;
  double max_value = 0.0;
  cv::minMaxLoc(acc, nullptr, &max_value);
  if (max_value <= 0.0) return min_value;
  std::vector<int> histogram(kBins, 0);
  const float scale = static_cast<float>((kBins - 1) / max_value);
  for (int y = 0; y < acc.rows; ++y) {
    const float* row = acc.ptr<float>(y);
    for (int x = 0; x < acc.cols; ++x) ++histogram[static_cast<size_t>(std::max(0.0f, row[x]) * scale)];
  }
  const auto rank = static_cast<long>(std::clamp(quantile, 0.0, 1.0) * static_cast<double>(acc.total() - 1));
  long seen = 0;
  int bin = 0;
  for (; bin < kBins - 1; ++bin) {
    seen += histogram[static_cast<size_t>(bin)];
    if (seen > rank) break;
  }
  return std::max(bin / static_cast<double>(scale), min_value);
}

std::vector<Blob> extract_blobs(const cv::Mat& acc, double threshold, int closing_size_px, double edge_band_px,
                                BoxFit fit, int connectivity, int min_pixels) {
  if (connectivity != 4 && connectivity != 8) throw InvalidArgument("extract_blobs: connectivity must be 4 or 8");
  std::vector<Blob> blobs;
  if (acc.empty()) return blobs;
  cv::Mat binary = (acc >= std::max(threshold, 1e-6));
  cv::Mat labels, stats, centroids;
  const int count = cv::connectedComponentsWithStats(binary, labels, stats, centroids, connectivity, CV_32S);
  const int pad = closing_size_px / 2 + 1;
  const cv::Mat element = cv::getStructuringElement(cv::MORPH_RECT, cv::Size(closing_size_px, closing_size_px));
  for (int label = 1; label < count; ++label) {
    const int area = stats.at<int>(label, cv::CC_STAT_AREA);
    if (area < min_pixels) continue;
    const cv::Rect bounds(stats.at<int>(label, cv::CC_STAT_LEFT), stats.at<int>(label, cv::CC_STAT_TOP),
                          stats.at<int>(label, cv::CC_STAT_WIDTH), stats.at<int>(label, cv::CC_STAT_HEIGHT));
    // The component alone, with room for closing to grow it.
    cv::Mat mask = cv::Mat::zeros(bounds.height + 2 * pad, bounds.width + 2 * pad, CV_8U);
    double strength = 0.0;
    for (int y = 0; y < bounds.height; ++y) {
      const int* l = labels.ptr<int>(bounds.y + y) + bounds.x;
      const float* a = acc.ptr<float>(bounds.y + y) + bounds.x;
      uchar* m = mask.ptr<uchar>(y + pad) + pad;
      for (int x = 0; x < bounds.width; ++x) {
        if (l[x] == label) {
          m[x] = 255;
          strength += a[x];
        }
      }
    }
    if (closing_size_px > 1) cv::morphologyEx(mask, mask, cv::MORPH_CLOSE, element);
    std::vector<std::vector<cv::Point>> contours;
    cv::findContours(mask, contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_NONE);
    if (contours.empty()) continue;
    cv::RotatedRect rect;
    if (fit == BoxFit::MinAreaRect) {
      // Closing may leave pieces; the outline of all of them is the blob.
      std::vector<cv::Point> outline;
      for (const auto& c : contours) outline.insert(outline.end(), c.begin(), c.end());
      rect = cv::minAreaRect(outline);
      rect.size += cv::Size2f(1.0f, 1.0f);  // pixel centres -> the pixels' extent
    } else {
      mask.setTo(0);
      cv::drawContours(mask, contours, -1, cv::Scalar(255), cv::FILLED);  // fill holes
      rect = moment_box(mask);
    }
    rect.center += cv::Point2f(static_cast<float>(bounds.x - pad), static_cast<float>(bounds.y - pad));
    const float shrink = static_cast<float>(2.0 * edge_band_px);
    rect.size.width = std::max(1.0f, rect.size.width - shrink);
    rect.size.height = std::max(1.0f, rect.size.height - shrink);
    Blob blob;
    blob.box = oriented_box_from_rotated_rect(rect);
    blob.pixel_count = area;
    blob.mean_strength = strength / area;
    blobs.push_back(blob);
  }
  return blobs;
}

}  // namespace uavmot::segmentation
