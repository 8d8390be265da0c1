#include "uavmot/segmentation/blob_regions.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <opencv2/imgproc.hpp>

#include "binary_mask.hpp"
#include "uavmot/core/error.hpp"

namespace uavmot::segmentation {
namespace {

// The rectangle with the same area moments as the filled mask: a uniformly filled L x W
// rectangle has variance L^2 / 12 along its length; sampling it on the pixel grid adds each
// pixel's own 1/12 in every direction, which is removed, so rotated shapes are not inflated.
// The moments are summed here (as cv::moments(mask, true) does, exactly, without its set-up cost).
cv::RotatedRect moment_box(const cv::Mat& mask) {
  double m00 = 0, m10 = 0, m01 = 0, m20 = 0, m11 = 0, m02 = 0;
  for (int y = 0; y < mask.rows; ++y) {
    const uchar* row = mask.ptr<uchar>(y);
    // Integer sums per row are exact; doubles across rows as in OpenCV.
    int64_t n = 0, sx = 0, sxx = 0;
    for (int x = 0; x < mask.cols; ++x) {
      if (row[x] == 0) continue;
      ++n;
      sx += x;
      sxx += static_cast<int64_t>(x) * x;
    }
    const double yd = y;
    m00 += static_cast<double>(n);
    m10 += static_cast<double>(sx);
    m20 += static_cast<double>(sxx);
    m01 += static_cast<double>(n) * yd;
    m11 += static_cast<double>(sx) * yd;
    m02 += static_cast<double>(n) * yd * yd;
  }
  if (m00 <= 0.0) return {};
  const double cx = m10 / m00, cy = m01 / m00;
  const double a = (m20 - cx * m10) / m00, b = (m11 - cx * m01) / m00, c = (m02 - cy * m01) / m00;
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

namespace {

struct ExtractParams {
  int closing_size_px;
  double edge_band_px;
  BoxFit fit;
  int connectivity;
  int min_pixels;
  SplitRule split;
};

// Closes and hole-fills one labelled component and fits its box.
Blob fit_component(const cv::Mat& acc, const cv::Mat& labels, int label, const cv::Rect& bounds, int area,
                   const ExtractParams& p, bool& ok) {
  ok = false;
  const int pad = p.closing_size_px / 2 + 1;
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
  close_binary(mask, p.closing_size_px);
  Blob blob;
  cv::RotatedRect rect;
  if (p.fit == BoxFit::MinAreaRect) {
    // Closing may leave pieces; the hull of all of them is the blob. The first and last set pixel
    // of every row span the same hull as the outline.
    std::vector<cv::Point> outline;
    for (int y = 0; y < mask.rows; ++y) {
      const uchar* row = mask.ptr<uchar>(y);
      int first = -1, last = -1;
      for (int x = 0; x < mask.cols; ++x) {
        if (row[x] == 0) continue;
        if (first < 0) first = x;
        last = x;
      }
      if (first < 0) continue;
      outline.emplace_back(first, y);
      if (last != first) outline.emplace_back(last, y);
    }
    if (outline.empty()) return blob;
    rect = cv::minAreaRect(outline);
    rect.size += cv::Size2f(1.0f, 1.0f);  // pixel centres -> the pixels' extent
  } else {
    fill_holes(mask);
    rect = moment_box(mask);
    if (rect.size.area() <= 0.0f) return blob;
  }
  rect.center += cv::Point2f(static_cast<float>(bounds.x - pad), static_cast<float>(bounds.y - pad));
  const float shrink = static_cast<float>(2.0 * p.edge_band_px);
  rect.size.width = std::max(1.0f, rect.size.width - shrink);
  rect.size.height = std::max(1.0f, rect.size.height - shrink);
  blob.box = oriented_box_from_rotated_rect(rect);
  blob.pixel_count = area;
  blob.mean_strength = strength / area;
  ok = true;
  return blob;
}

bool too_big(const OrientedBox& box, const SplitRule& rule) {
  return (rule.max_length_px > 0.0 && box.length > rule.max_length_px) ||
         (rule.max_width_px > 0.0 && box.width > rule.max_width_px);
}

void extract(const cv::Mat& acc, const cv::Mat& binary, double threshold, const ExtractParams& p, bool may_split,
             std::vector<Blob>& blobs) {
  cv::Mat labels, stats, centroids;
  const int count = cv::connectedComponentsWithStats(binary, labels, stats, centroids, p.connectivity, CV_32S);
  for (int label = 1; label < count; ++label) {
    const int area = stats.at<int>(label, cv::CC_STAT_AREA);
    if (area < p.min_pixels) continue;
    const cv::Rect bounds(stats.at<int>(label, cv::CC_STAT_LEFT), stats.at<int>(label, cv::CC_STAT_TOP),
                          stats.at<int>(label, cv::CC_STAT_WIDTH), stats.at<int>(label, cv::CC_STAT_HEIGHT));
    bool ok = false;
    const Blob blob = fit_component(acc, labels, label, bounds, area, p, ok);
    if (!ok) continue;
    if (may_split && too_big(blob.box, p.split)) {
      // Larger than one vehicle: raise the threshold on this component alone until it falls
      // apart into several sizeable parts (the weak pixels between two cars go first).
      const cv::Mat component = labels(bounds) == label;
      double peak = 0.0;
      cv::minMaxLoc(acc(bounds), nullptr, &peak, nullptr, nullptr, component);
      bool split = false;
      for (int level = 1; level <= p.split.levels && !split; ++level) {
        const double raised = threshold + (peak - threshold) * level / (p.split.levels + 1.0);
        cv::Mat part = cv::Mat::zeros(acc.size(), CV_8U);
        part(bounds).setTo(255, component & (acc(bounds) >= raised));
        cv::Mat part_labels, part_stats, part_centroids;
        const int parts = cv::connectedComponentsWithStats(part, part_labels, part_stats, part_centroids, p.connectivity, CV_32S);
        int sizeable = 0;
        for (int i = 1; i < parts; ++i) sizeable += part_stats.at<int>(i, cv::CC_STAT_AREA) >= p.split.min_part_pixels ? 1 : 0;
        if (sizeable < 2) continue;
        ExtractParams parts_params = p;
        parts_params.min_pixels = std::max(p.min_pixels, p.split.min_part_pixels);
        extract(acc, part, raised, parts_params, false, blobs);
        split = true;
      }
      if (split) continue;
    }
    blobs.push_back(blob);
  }
}

}  // namespace

std::vector<Blob> extract_blobs(const cv::Mat& acc, double threshold, int closing_size_px, double edge_band_px,
                                BoxFit fit, int connectivity, int min_pixels, const SplitRule& split) {
  if (connectivity != 4 && connectivity != 8) throw InvalidArgument("extract_blobs: connectivity must be 4 or 8");
  std::vector<Blob> blobs;
  if (acc.empty()) return blobs;
  const cv::Mat binary = (acc >= std::max(threshold, 1e-6));
  extract(acc, binary, threshold, {closing_size_px, edge_band_px, fit, connectivity, min_pixels, split}, true, blobs);
  return blobs;
}

std::vector<GroupedBlob> group_vehicle_parts(const std::vector<Blob>& blobs, double max_length_px, double max_width_px,
                                             double touch_px) {
  std::vector<size_t> order(blobs.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t a, size_t b) { return blobs[a].pixel_count > blobs[b].pixel_count; });
  const bool enabled = max_length_px > 0.0 && max_width_px > 0.0;
  std::vector<GroupedBlob> groups;
  std::vector<std::vector<cv::Point2f>> corners;
  for (size_t index : order) {
    const Blob& blob = blobs[index];
    std::vector<cv::Point2f> own;
    for (const auto& c : box_corners(blob.box)) own.emplace_back(static_cast<float>(c.x), static_cast<float>(c.y));
    OrientedBox touching = blob.box;
    touching.length += 2.0 * touch_px;
    touching.width += 2.0 * touch_px;
    bool joined = false;
    for (size_t g = 0; enabled && g < groups.size() && !joined; ++g) {
      if (intersection_area(touching, groups[g].box) <= 0.0) continue;
      std::vector<cv::Point2f> all = corners[g];
      all.insert(all.end(), own.begin(), own.end());
      const OrientedBox combined = oriented_box_from_rotated_rect(cv::minAreaRect(all));
      if (combined.length > max_length_px || combined.width > max_width_px) continue;
      groups[g].box = combined;
      groups[g].pixel_count += blob.pixel_count;
      ++groups[g].parts;
      corners[g] = std::move(all);
      joined = true;
    }
    if (!joined) {
      groups.push_back({blob.box, blob.pixel_count, 1});
      corners.push_back(std::move(own));
    }
  }
  return groups;
}

}  // namespace uavmot::segmentation
