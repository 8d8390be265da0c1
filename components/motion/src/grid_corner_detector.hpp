#pragma once
// Shi-Tomasi corners, detected only in grid cells that hold too few live features, so a frame
// with good coverage costs almost nothing and new texture entering the view is picked up.

#include <cstdint>
#include <utility>
#include <vector>

#include <opencv2/core/mat.hpp>
#include <opencv2/core/types.hpp>

#include "change_mask.hpp"
#include "uavmot/core/homography.hpp"
#include "uavmot/motion/motion_options.hpp"

namespace uavmot::motion {

// Side of the detection grid cells for an image of `size`: cell_size_px, or when that is 0, the
// size at which the cells hold max_features (features_per_cell each), so feature density follows
// the image size.
int detection_cell_size(const MotionOptions& options, cv::Size size);

// New corners in `gray` (CV_8UC1): at least min_distance_px from every point of `existing` and
// from each other, at most features_per_cell per cell counting `existing`, no more than
// max_features in total, above min_corner_response. Deterministic order: when the budget cannot
// serve every cell that lacks features, the cells whose 3x3 neighbourhood holds the fewest features
// first (ties row-major), so the budget goes where the image is least covered; strongest corner
// first within a cell. The response (min_eigen_map.hpp) is computed for the searched cells only.
// Corners lie border_px inside `picture` (active_picture.hpp; empty: the whole image), here and below.
std::vector<cv::Point2f> detect_missing_corners(const cv::Mat& gray, const std::vector<cv::Point2f>& existing,
                                                const MotionOptions& options, const cv::Rect& picture = {});

// Corners on changed pixels (`changed`: CV_8UC1, non-zero = changed, `gray`'s size): in every cell
// with changed pixels, whatever it already holds, up to change_features_per_cell new ones there,
// at least min_distance_px from every point of `existing` and from each other, at most `budget` in
// all. Cells with the most changed pixels first (ties row-major), strongest corner first.
// With `blobs`, only the pixels of compact blobs of `changed` count (ChangeBlobs, change_mask.hpp).
// `changed` may be a coarser level's mask, each of its pixels covering `scale` x `scale` pixels of
// `gray` (its size then `gray`'s divided by `scale`, rounded up).
std::vector<cv::Point2f> detect_changed_corners(const cv::Mat& gray, const cv::Mat& changed,
                                                const std::vector<cv::Point2f>& existing, const MotionOptions& options,
                                                int budget, ChangeBlobs* blobs = nullptr, int scale = 1,
                                                const cv::Rect& picture = {});

// The same, remembering cells that gave no new corner (flat ground, sky, a blank frame, or every
// corner too close to a live feature) and searching them again only after `empty_cell_retry_frames`
// calls (staggered by cell), so such areas do not cost a corner search every frame; sooner where
// `motion` (the last frame to this one) moves the image at the cell by empty_cell_retry_shift_cells
// cells in fewer frames, since new ground is then in view there. With `continuous` false (first
// frame, after an invalid one) every cell is searched and the back-off starts afresh: after a blank
// frame, the next frame must be searched everywhere.
class GridCornerDetector {
 public:
  explicit GridCornerDetector(const MotionOptions& options) : options_(options) {}
  // `response_scale` multiplies min_corner_response in this call (a low-contrast frame).
  std::vector<cv::Point2f> detect(const cv::Mat& gray, const std::vector<cv::Point2f>& existing, bool continuous,
                                  double response_scale = 1.0, const Homography& motion = Homography::eye(),
                                  const cv::Rect& picture = {});
  void reset() {  // as constructed
    retry_at_.clear();
    calls_ = 0;
  }

  // What carries over from call to call (a saved estimator state).
  struct State {
    int64_t calls = 0;
    cv::Size size;
    std::vector<int64_t> retry_at;
  };
  State state() const { return {calls_, size_, retry_at_}; }
  int64_t calls() const { return calls_; }  // frames searched since construction or reset()
  void restore(State state) {
    calls_ = state.calls;
    size_ = state.size;
    retry_at_ = std::move(state.retry_at);
  }

 private:
  const MotionOptions& options_;
  int64_t calls_ = 0;
  cv::Size size_;
  std::vector<int64_t> retry_at_;  // per cell: first call at which an empty cell is searched again
};

}  // namespace uavmot::motion
