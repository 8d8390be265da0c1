#pragma once
// Does a region move with its cluster, or is it static texture that the cluster's window holds
// (a lane marking beside a car, the kerb behind it)? Both pass the gradients and the feature
// support test; only the previous frame tells them apart. Carried through the homography, the
// previous frame explains a static region unshifted and a moving one shifted by the cluster's
// velocity.

#include <optional>
#include <vector>

#include <opencv2/core/mat.hpp>
#include <opencv2/core/types.hpp>

#include "uavmot/core/homography.hpp"
#include "uavmot/core/oriented_box.hpp"
#include "uavmot/segmentation/segmenter.hpp"

namespace uavmot::segmentation {

// Mean absolute grey difference over the region's pixels between the current frame and the
// previous one sampled where each pixel was if static, and where it was if it moved with the
// cluster (the best of the shifts searched).
struct ShiftErrors {
  double static_error = 0.0;
  double moving_error = 0.0;
  int pixels = 0;
};

struct ShiftSearch {
  cv::Vec2d velocity;       // the cluster's motion relative to the background, px/frame
  double radius_px = 0.0;   // also try velocity + (dx, dy) for dx, dy in {-r, 0, r}: feature velocities are estimates
  double min_speed_px = 0;  // shifts slower than this are not a moving hypothesis (they would explain static texture)
};

// The shifts a moving hypothesis tries: the velocity, and +-radius in x and y around it, each at
// least min_speed_px long (row by row, the velocity itself first).
std::vector<cv::Point2d> shifts_to_try(const ShiftSearch& search);

// What comparing a box with the previous frame needs: the box's pixel bounds within `current`, the
// previous window that holds most of them both at rest and moved back by the search velocity (the
// window of the same cluster, usually; a region at the edge of a cluster's window, as static
// texture beside a car often is, may be held only in part, as the window moved with the car), and
// where each shift of shifts_to_try moves a previous-frame position: over a region's few pixels the
// homography is affine to well below a thousandth of a pixel, so by the Jacobian at the box's centre
// times the shift. Nothing when no shift is fast enough, the box is not finite, it holds no pixel of
// `current`, or no previous window holds any of it.
struct PreviousFrameView {
  cv::Rect bounds;
  const ImageCrop* source = nullptr;
  std::vector<cv::Point2d> offsets;
  cv::Point2d lowest, highest;  // the smallest and largest offset each way, the zero one included

  // Whether the source window holds `rest` (a previous-frame position) at rest and under every
  // shift. The window is a rectangle, so it holds them all when it holds the extreme ones.
  bool holds_every_shift(const cv::Point2d& rest) const;
};
std::optional<PreviousFrameView> previous_frame_view(const ImageCrop& current, const OrientedBox& box, const ShiftSearch& search,
                                                     const Homography& previous_from_current,
                                                     const std::vector<ImageCrop>& previous);

// `current` (grey, CV_8UC1) holds the region: its window of the current frame; `previous` are grey
// windows of the previous frame; `previous_from_current` maps current-frame to previous-frame
// coordinates. Nothing when no shift is fast enough, no window of `previous` holds at least half
// the region's pixels under every hypothesis, or the box holds no pixel of `current`.
std::optional<ShiftErrors> compare_shifts(const ImageCrop& current, const OrientedBox& box, const ShiftSearch& search,
                                          const Homography& previous_from_current, const std::vector<ImageCrop>& previous);

// Whether `candidate` matches the previous frame shifted (its best shift) better, relative to at
// rest, than a box whose compare_shifts gave `reference`: the ratio moving / static error is lower.
// False when `candidate` cannot be compared; true when only the reference could not be.
bool moves_more_plainly(const ImageCrop& current, const OrientedBox& candidate, const std::optional<ShiftErrors>& reference,
                        const ShiftSearch& search, const Homography& previous_from_current,
                        const std::vector<ImageCrop>& previous);

}  // namespace uavmot::segmentation
