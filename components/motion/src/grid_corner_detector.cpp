#include "grid_corner_detector.hpp"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

#include "active_picture.hpp"
#include "min_eigen_map.hpp"

namespace uavmot::motion {
namespace {

struct Candidate {
  float response;
  int x;
  int y;
};

// Points already placed, bucketed by grid cell for the min-distance test.
class CellBuckets {
 public:
  CellBuckets(int cols, int rows, int cell, double min_distance)
      : cols_(cols), rows_(rows), cell_(cell), min_distance2_(min_distance * min_distance),
        reach_(static_cast<int>(std::ceil(min_distance / cell))), buckets_(static_cast<size_t>(cols * rows)) {}

  int cell_of(const cv::Point2f& p) const {
    const int cx = std::clamp(static_cast<int>(p.x) / cell_, 0, cols_ - 1);
    const int cy = std::clamp(static_cast<int>(p.y) / cell_, 0, rows_ - 1);
    return cy * cols_ + cx;
  }
  void add(const cv::Point2f& p) { buckets_[static_cast<size_t>(cell_of(p))].push_back(p); }
  int count(int cell_index) const { return static_cast<int>(buckets_[static_cast<size_t>(cell_index)].size()); }

  bool is_free(const cv::Point2f& p) const {
    const int c = cell_of(p);
    const int cx = c % cols_, cy = c / cols_;
    for (int y = std::max(0, cy - reach_); y <= std::min(rows_ - 1, cy + reach_); ++y) {
      for (int x = std::max(0, cx - reach_); x <= std::min(cols_ - 1, cx + reach_); ++x) {
        for (const auto& q : buckets_[static_cast<size_t>(y * cols_ + x)]) {
          const float dx = p.x - q.x, dy = p.y - q.y;
          if (static_cast<double>(dx * dx + dy * dy) < min_distance2_) return false;
        }
      }
    }
    return true;
  }

 private:
  int cols_, rows_, cell_;
  double min_distance2_;
  int reach_;
  std::vector<std::vector<cv::Point2f>> buckets_;
};

// Local maxima of the corner response inside `cell` (image coordinates), strongest first. The
// response is computed for the cell and its one-pixel rim (the neighbours of the local-maximum
// test), exactly and at the search's threshold as floor (min_eigen_map.hpp): most searched cells
// are flat or plain edges and cost no square root.
std::vector<Candidate> cell_candidates(const cv::Mat& gray, const cv::Rect& cell, const MotionOptions& o) {
  const cv::Rect roi = cv::Rect(cell.x - 1, cell.y - 1, cell.width + 2, cell.height + 2) & cv::Rect(0, 0, gray.cols, gray.rows);
  cv::Mat eig;
  min_eigen_values(gray, roi, o.corner_block_size, o.min_corner_response, eig);
  const auto threshold = static_cast<float>(o.min_corner_response);
  std::vector<Candidate> out;
  for (int y = cell.y; y < cell.y + cell.height; ++y) {
    const int ry = y - roi.y;
    if (ry < 1 || ry >= eig.rows - 1) continue;
    const float* above = eig.ptr<float>(ry - 1);
    const float* row = eig.ptr<float>(ry);
    const float* below = eig.ptr<float>(ry + 1);
    for (int x = cell.x; x < cell.x + cell.width; ++x) {
      const int rx = x - roi.x;
      if (rx < 1 || rx >= eig.cols - 1) continue;
      const float v = row[rx];
      if (v < threshold || v <= 0.0f) continue;
      if (v < row[rx - 1] || v < row[rx + 1] || v < above[rx - 1] || v < above[rx] || v < above[rx + 1] ||
          v < below[rx - 1] || v < below[rx] || v < below[rx + 1]) {
        continue;
      }
      out.push_back({v, x, y});
    }
  }
  std::sort(out.begin(), out.end(), [](const Candidate& a, const Candidate& b) {
    if (a.response != b.response) return a.response > b.response;
    if (a.y != b.y) return a.y < b.y;
    return a.x < b.x;
  });
  return out;
}

}  // namespace

int detection_cell_size(const MotionOptions& o, cv::Size size) {
  if (o.cell_size_px > 0) return o.cell_size_px;
  const double area = static_cast<double>(size.width) * size.height;
  const double cell = std::sqrt(area * o.features_per_cell / std::max(1, o.max_features));
  return std::clamp(static_cast<int>(std::lround(cell)), 8, 1024);
}

namespace {

// The detection grid over `gray` with the live features bucketed: what both detectors start from.
struct DetectionGrid {
  DetectionGrid(cv::Size size, const cv::Rect& picture, const std::vector<cv::Point2f>& existing, const MotionOptions& o)
      : cell(detection_cell_size(o, size)),
        cols((size.width + cell - 1) / cell),
        rows((size.height + cell - 1) / cell),
        usable(usable_area(picture.empty() ? cv::Rect(cv::Point(), size) : picture, o.border_px)),
        buckets(cols, rows, cell, o.min_distance_px) {
    for (const auto& p : existing) buckets.add(p);
  }
  bool empty() const { return usable.width <= 0 || usable.height <= 0; }
  // Cell `index`'s pixels away from the border (may be empty).
  cv::Rect area(int index) const { return cv::Rect((index % cols) * cell, (index / cols) * cell, cell, cell) & usable; }

  int cell, cols, rows;
  cv::Rect usable;
  CellBuckets buckets;
};

// Frames an empty cell waits before it is searched again: empty_cell_retry_frames, or fewer where
// `motion` moves the image at the cell's centre by empty_cell_retry_shift_cells cells sooner.
int empty_cell_wait(const cv::Rect& area, int cell, const Homography& motion, const MotionOptions& o) {
  const int wait = o.empty_cell_retry_frames;
  if (o.empty_cell_retry_shift_cells <= 0.0 || wait <= 1) return wait;
  const double shift_px = image_step_px(motion, {area.x + 0.5 * area.width, area.y + 0.5 * area.height});
  if (!(shift_px > 0.0)) return wait;
  const double frames = std::ceil(o.empty_cell_retry_shift_cells * cell / shift_px);
  return frames >= wait ? wait : std::max(1, static_cast<int>(frames));
}

// Shared by both entry points; `retry_at` (may be null) holds the empty-cell back-off.
std::vector<cv::Point2f> detect_in_cells(const cv::Mat& gray, const cv::Rect& picture,
                                         const std::vector<cv::Point2f>& existing, const MotionOptions& o,
                                         std::vector<int64_t>* retry_at, int64_t call, const Homography& motion) {
  std::vector<cv::Point2f> added;
  int budget = o.max_features - static_cast<int>(existing.size());
  if (budget <= 0 || gray.empty()) return added;
  DetectionGrid grid(gray.size(), picture, existing, o);
  if (grid.empty()) return added;
  const int cols = grid.cols, rows = grid.rows;
  CellBuckets& buckets = grid.buckets;
  // Emptiest neighbourhoods first: when the feature budget is smaller than the cells to fill, it
  // goes where the image is least covered (the edge where new ground enters), not to the cells
  // that come first in row-major order (which starved the bottom and right of large frames).
  std::vector<std::pair<int, int>> to_search;  // (features in the 3x3 cell neighbourhood, cell)
  for (int index = 0; index < cols * rows; ++index) {
    if (buckets.count(index) >= o.features_per_cell) continue;
    if (retry_at && (*retry_at)[static_cast<size_t>(index)] > call) continue;
    const int cx = index % cols, cy = index / cols;
    int around = 0;
    for (int y = std::max(0, cy - 1); y <= std::min(rows - 1, cy + 1); ++y)
      for (int x = std::max(0, cx - 1); x <= std::min(cols - 1, cx + 1); ++x) around += buckets.count(y * cols + x);
    to_search.emplace_back(around, index);
  }
  if (static_cast<int>(to_search.size()) > budget) std::stable_sort(to_search.begin(), to_search.end());
  for (const auto& [around, index] : to_search) {
    if (budget <= 0) break;
    const cv::Rect area = grid.area(index);
    if (area.width <= 0 || area.height <= 0) continue;
    const auto candidates = cell_candidates(gray, area, o);
    bool placed = false;
    for (const auto& c : candidates) {
      const cv::Point2f p(static_cast<float>(c.x), static_cast<float>(c.y));
      if (!buckets.is_free(p)) continue;
      buckets.add(p);
      added.push_back(p);
      placed = true;
      --budget;
      if (buckets.count(index) >= o.features_per_cell || budget <= 0) break;
    }
    if (retry_at) {
      // A cell that gave nothing (no corner, or every corner too close to a live feature) waits;
      // the wait is staggered by cell so the retries do not all land on the same frame.
      int64_t& retry = (*retry_at)[static_cast<size_t>(index)];
      if (placed) {
        retry = 0;
      } else {
        const int wait = empty_cell_wait(area, grid.cell, motion, o);
        retry = call + wait + (wait > 1 ? index % wait : 0);
      }
    }
  }
  return added;
}

}  // namespace

std::vector<cv::Point2f> detect_missing_corners(const cv::Mat& gray, const std::vector<cv::Point2f>& existing,
                                                const MotionOptions& o, const cv::Rect& picture) {
  return detect_in_cells(gray, picture, existing, o, nullptr, 0, Homography::eye());
}

std::vector<cv::Point2f> detect_changed_corners(const cv::Mat& gray, const cv::Mat& changed,
                                                const std::vector<cv::Point2f>& existing, const MotionOptions& o,
                                                int budget, ChangeBlobs* blobs, int scale, const cv::Rect& picture) {
  std::vector<cv::Point2f> added;
  if (budget <= 0 || gray.empty() || scale < 1 ||
      changed.size() != cv::Size((gray.cols + scale - 1) / scale, (gray.rows + scale - 1) / scale)) {
    return added;
  }
  DetectionGrid grid(gray.size(), picture, existing, o);
  if (grid.empty()) return added;
  // Changed pixels per cell (within the usable area; with `blobs`, those of compact blobs only):
  // each set pixel of the mask counts the full-size pixels it covers, in one pass over the mask.
  std::vector<int> counts(static_cast<size_t>(grid.cols * grid.rows), 0);
  const cv::Rect& usable = grid.usable;
  for (int my = usable.y / scale; my <= (usable.br().y - 1) / scale; ++my) {
    const uchar* row = changed.ptr<uchar>(my);
    for (int mx = usable.x / scale; mx <= (usable.br().x - 1) / scale; ++mx) {
      if (row[mx] == 0) continue;
      const int y0 = std::max(usable.y, my * scale), y1 = std::min(usable.br().y, (my + 1) * scale);
      const int x0 = std::max(usable.x, mx * scale), x1 = std::min(usable.br().x, (mx + 1) * scale);
      if (blobs != nullptr && !blobs->compact_at(x0, y0)) continue;  // one blob for all it covers
      for (int y = y0; y < y1; ++y) {
        int* cell_counts = counts.data() + static_cast<size_t>(y / grid.cell) * grid.cols;
        for (int x = x0; x < x1; ++x) ++cell_counts[x / grid.cell];
      }
    }
  }
  std::vector<std::pair<int, int>> to_search;  // (-changed pixels, cell): most changed first
  for (int index = 0; index < grid.cols * grid.rows; ++index) {
    if (const int count = counts[static_cast<size_t>(index)]; count > 0) to_search.emplace_back(-count, index);
  }
  std::sort(to_search.begin(), to_search.end());
  for (const auto& [minus_count, index] : to_search) {
    if (budget <= 0) break;
    int placed = 0;
    for (const auto& c : cell_candidates(gray, grid.area(index), o)) {
      if (!changed.at<uchar>(c.y / scale, c.x / scale) || (blobs != nullptr && !blobs->compact_at(c.x, c.y))) continue;
      const cv::Point2f p(static_cast<float>(c.x), static_cast<float>(c.y));
      if (!grid.buckets.is_free(p)) continue;
      grid.buckets.add(p);
      added.push_back(p);
      --budget;
      if (++placed >= o.change_features_per_cell || budget <= 0) break;
    }
  }
  return added;
}

std::vector<cv::Point2f> GridCornerDetector::detect(const cv::Mat& gray, const std::vector<cv::Point2f>& existing,
                                                    bool continuous, double response_scale, const Homography& motion,
                                                    const cv::Rect& picture) {
  const int cell = detection_cell_size(options_, gray.size());
  const size_t cells = static_cast<size_t>(((gray.cols + cell - 1) / cell) * ((gray.rows + cell - 1) / cell));
  if (!continuous || gray.size() != size_ || retry_at_.size() != cells) {
    size_ = gray.size();
    retry_at_.assign(cells, 0);
  }
  if (response_scale == 1.0) return detect_in_cells(gray, picture, existing, options_, &retry_at_, calls_++, motion);
  MotionOptions scaled = options_;
  scaled.min_corner_response *= response_scale;
  return detect_in_cells(gray, picture, existing, scaled, &retry_at_, calls_++, motion);
}

}  // namespace uavmot::motion
