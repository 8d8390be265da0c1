#pragma once
// Pyramidal Lucas-Kanade on pyramids built once per frame (with derivatives), so each frame's
// pyramid serves as "next" for the forward track and as "previous" for the next frame and for
// the backward check.

#include <vector>

#include <opencv2/core/mat.hpp>
#include <opencv2/core/types.hpp>

#include "uavmot/motion/motion_options.hpp"

namespace uavmot::motion {

struct Pyramid {
  std::vector<cv::Mat> levels;  // cv::buildOpticalFlowPyramid layout (image, derivatives, ...)
  cv::Size size;
  cv::Rect picture;  // the image inside its black bands (active_picture.hpp)
  bool empty() const { return levels.empty(); }
};

// Builds the pyramid of `gray` into `pyramid`, reusing its buffers when the size matches, and finds
// its picture area.
void build_pyramid(const cv::Mat& gray, const MotionOptions& options, Pyramid& pyramid);

// Tracks `from` (in `previous`) into `current`, starting at `guess`, on `levels` pyramid levels above
// full resolution (at most the pyramids'). `tracked[i]` is set where the
// forward track converged, the backward track returns within max_forward_backward_px and the
// result lies border_px inside `current`'s picture area. `corner_strength[i]` is the minimum eigenvalue of the
// point's LK window in `previous`, in min_corner_response's units (cv::cornerMinEigenVal's).
void track_features(const Pyramid& previous, const Pyramid& current, const std::vector<cv::Point2f>& from,
                    const std::vector<cv::Point2f>& guess, int levels, const MotionOptions& options,
                    std::vector<cv::Point2f>& to, std::vector<unsigned char>& tracked,
                    std::vector<float>& corner_strength);

// Global translation from `previous` to `current` by phase correlation on a coarse pyramid level
// (the coarsest whose smaller side is at least 64 px), in full-resolution pixels. Used to recover
// when the previous motion is no guide (a jump, dropped frames). `confident` is false when the
// correlation peak is weak.
cv::Point2d coarse_translation(const Pyramid& previous, const Pyramid& current, bool& confident);

}  // namespace uavmot::motion
