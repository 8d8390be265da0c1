#pragma once
// The residual motion of the background that a homography cannot express: lens distortion and
// gentle relief leave a smooth field of small relative velocities (0.1-0.6 px/frame on the real
// CLIF frames) that would otherwise make whole image regions "move". A robust low-order
// polynomial fit of the features' relative velocities over the image captures that field; moving
// vehicles are few and small, so the robust weights ignore them.

#include <algorithm>
#include <vector>

#include <opencv2/core/matx.hpp>
#include <opencv2/core/types.hpp>

namespace uavmot::motion {

class BackgroundFlow {
 public:
  // `degree` 0 disables the model (field() is zero); 1 affine, 2 quadratic, 3 cubic.
  BackgroundFlow(int degree, cv::Size image_size) : degree_(std::min(degree, kMaxDegree)), size_(image_size) {}

  // Robust fit (Tukey biweight, iteratively reweighted, started from a zero field) of velocities
  // at positions. Leaves the field zero when there are fewer than 3 points per coefficient.
  void fit(const std::vector<cv::Point2f>& positions, const std::vector<cv::Vec2d>& velocities);

  cv::Vec2d field(const cv::Point2f& p) const;

 private:
  static constexpr int kMaxDegree = 4;  // the option's range (motion_options.cpp)
  static constexpr int kMaxTerms = (kMaxDegree + 1) * (kMaxDegree + 2) / 2;
  // Writes the monomials x^i y^j (i + j <= degree) at p into `out`; returns how many.
  int basis(const cv::Point2f& p, double* out) const;

  int degree_;
  cv::Size size_;
  std::vector<double> cx_, cy_;  // coefficients, empty when not fitted
};

}  // namespace uavmot::motion
