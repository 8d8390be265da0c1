#pragma once
// Where the image changed once the camera's motion is taken out: the previous frame warped by the
// frame's homography against this one. Moving vehicles (and, under parallax, structure) light up;
// the ground does not. The detector seeds features there, so a small vehicle crossing a grid cell
// that already holds a ground feature still gets one (docs/motion.md, "Features seeded on change").

#include <vector>

#include <opencv2/core/mat.hpp>

#include "uavmot/core/homography.hpp"
#include "uavmot/motion/motion_options.hpp"

namespace uavmot::motion {

// CV_8UC1 mask of `current`'s size, 255 where |current - warped previous| exceeds
// max(change_min_grey, change_threshold_sigma x the difference's robust sigma), 0 elsewhere and
// where the warped previous frame does not reach (its source pixel less than half a pixel inside
// the previous frame). `previous_to_current` maps previous to current pixels. Empty when either
// image is empty or their sizes differ.
cv::Mat changed_pixels(const cv::Mat& previous, const cv::Mat& current, const Homography& previous_to_current,
                       const MotionOptions& options);

// Whether a changed pixel belongs to a compact blob (8-connected, its bounding box at most
// `max_extent_px` on either side: a vehicle's change is its front and back edges, within its length
// and its step) or to a long one (3-D structure under parallax: a roof edge changes along its
// whole length). A bounded flood fill from the pixel asked about, each blob filled at most once;
// a few hundred questions per frame cost far less than labelling the whole mask.
class ChangeBlobs {
 public:
  // `changed` must outlive this object; it may be a mask of a coarser level, each of its pixels
  // covering `scale` x `scale` full-size pixels. max_extent_px (full-size pixels) <= 0: every blob
  // counts as compact.
  ChangeBlobs(const cv::Mat& changed, double max_extent_px, int scale = 1);
  // (x, y) in full-size pixels. False for an unchanged pixel.
  bool compact_at(int x, int y);

 private:
  const cv::Mat& changed_;
  int max_extent_;
  int scale_;
  cv::Mat verdict_;  // CV_8U: 0 not yet known, kCompact, kLong
  std::vector<int> stack_, visited_;
};

}  // namespace uavmot::motion
