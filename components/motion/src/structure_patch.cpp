#include "structure_patch.hpp"

#include <opencv2/imgproc.hpp>

namespace uavmot::motion {
namespace {

// Shifts per side: 0, cap/6, ..., cap along the line (twice as many less one when both ways). An
// odd count puts the track's own start among its shifts.
constexpr int kShiftsPerSide = 7;

// Lowers each pixel of `best` to its difference from `previous` around `centre`, if smaller.
void keep_smallest(const cv::Mat& previous, const cv::Mat& here, cv::Point2d centre, cv::Mat& best, cv::Mat& scratch) {
  cv::getRectSubPix(previous, here.size(), cv::Point2f(static_cast<float>(centre.x), static_cast<float>(centre.y)), scratch,
                    CV_32F);
  cv::absdiff(scratch, here, scratch);
  if (best.empty()) {
    scratch.copyTo(best);
  } else {
    cv::min(best, scratch, best);
  }
}

}  // namespace

PatchErrors structure_patch_errors(const cv::Mat& previous, const cv::Mat& current, cv::Point2f from, cv::Point2f to,
                                   const Homography& current_to_previous, const ParallaxFilter::StructureMotion& structure,
                                   int radius_px) {
  const cv::Size patch(2 * radius_px + 1, 2 * radius_px + 1);
  cv::Mat here, scratch, structure_best, own_best;
  cv::getRectSubPix(current, patch, to, here, CV_32F);
  const int shifts = structure.both_ways ? 2 * kShiftsPerSide - 1 : kShiftsPerSide;
  const double lowest = structure.both_ways ? -structure.cap_px : 0.0;
  const double step = (structure.cap_px - lowest) / (shifts - 1);
  const cv::Point2d u(structure.direction[0], structure.direction[1]);
  const cv::Point2d start(from);
  for (int i = 0; i < shifts; ++i) {
    const double s = lowest + step * i;
    // A static point at height: its parallax s along the line in this frame, the ground's motion before it.
    keep_smallest(previous, here, apply_homography(current_to_previous, cv::Point2d(to) - s * u), structure_best, scratch);
    // The track's own start, moved by up to half the cap either way.
    const double t = (static_cast<double>(i) / (shifts - 1) - 0.5) * structure.cap_px;
    keep_smallest(previous, here, start + t * u, own_best, scratch);
  }
  return {cv::mean(structure_best)[0], cv::mean(own_best)[0]};
}

bool structure_explains_patch(const PatchErrors& errors, const MotionOptions& options) {
  return options.structure_patch_ratio > 0.0 && errors.structure <= options.structure_patch_ratio * errors.own;
}

}  // namespace uavmot::motion
