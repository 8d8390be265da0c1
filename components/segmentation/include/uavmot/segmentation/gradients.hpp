#pragma once
// The three gradient segmentations of paper III-B. Each takes a grey (CV_8UC1) image window and
// returns its own accumulator (CV_32FC1, same size, >= 0), summed over several scales.
// Borders are replicated, so a window's result depends only on the window's pixels.

#include <cstdint>
#include <vector>

#include <opencv2/core/mat.hpp>

namespace uavmot::segmentation {

// 1D Gaussian-derivative kernel (odd length, antisymmetric, positive for x > 0) normalised
// after Korn (1988): the sum of its positive half is 1, so the filter's response to a unit
// step is 1 at both pixels beside the step, whatever the scale.
cv::Mat korn_derivative_kernel(double sigma_px);
// The matching smoothing kernel across the derivative direction (sum 1).
cv::Mat korn_smoothing_kernel(double sigma_px);

// Korn gradient: sum over `sigmas_px` of the normalised gradient magnitude (no directions,
// no non-maximum suppression). A step of height h gives about h * sigmas.size() on the edge.
cv::Mat korn_gradient(const cv::Mat& gray, const std::vector<double>& sigmas_px);

// Morphological gradient, eq. (1): sum over square elements s of dilate(I, s) - erode(I, s).
cv::Mat morphological_gradient(const cv::Mat& gray, const std::vector<int>& sizes_px);

// Rotation-invariant uniform LBP (Ojala 2002) of centre value `centre` and `neighbours`
// sampled around it: the number of neighbours >= centre when the circular pattern has at most
// two 0/1 transitions, else neighbours.size() + 1.
int lbp_riu2(double centre, const std::vector<double>& neighbours);

// A texture primitive (edge, corner, line end) is a uniform pattern that is neither all
// neighbours darker (0, a bright spot) nor all brighter-or-equal (P, flat or a dark spot).
inline bool is_texture_primitive(int riu2, int neighbours) { return riu2 >= 1 && riu2 <= neighbours - 1; }

// LBP gradient, eq. (2): for each radius r, every pixel whose LBP^riu2_{P,r} is a texture
// primitive and whose neighbours' standard deviation is at least `min_stddev` adds that
// standard deviation; other pixels add nothing. Neighbours are bilinearly interpolated.
// The pattern is tested on the image and on its negative: with Ojala's s(x) = [x >= 0] a pixel
// on the darker side of a step sees only equal or brighter neighbours (code P, "flat"), so the
// edge would be found on its bright side only; the negative finds the dark side, keeping the
// accumulator symmetric about the edge like the other two gradients.
cv::Mat lbp_gradient(const cv::Mat& gray, int neighbours, const std::vector<double>& radii_px, double min_stddev);

}  // namespace uavmot::segmentation
