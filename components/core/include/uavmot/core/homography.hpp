#pragma once
// Homographies map coordinates of frame k-1 to frame k (docs/conventions.md),
// stored row-major and normalised so h33 = 1.

#include <array>
#include <vector>

#include <opencv2/core/matx.hpp>
#include <opencv2/core/types.hpp>

#include "uavmot/core/oriented_box.hpp"

namespace uavmot {

using Homography = cv::Matx33d;

Homography identity_homography();
// Divides by h33; returns false (and leaves `h` untouched) when h33 is ~0 or any entry is not finite.
bool normalize_homography(Homography& h);
bool is_finite(const Homography& h);

cv::Point2d apply_homography(const Homography& h, const cv::Point2d& p);

// Local linearisation (Jacobian) of the homography at p: how a small displacement maps.
cv::Matx22d homography_jacobian(const Homography& h, const cv::Point2d& p);

// Maps an oriented box: centre exactly, axes through the local Jacobian.
OrientedBox transform_box(const Homography& h, const OrientedBox& box);

// How far the homography moves the point p (px): the ground's image motion there.
double image_step_px(const Homography& h, const cv::Point2d& p);

// How many frames the camera, at this homography's rate at the image centre, takes to carry the
// ground across the image's smaller side: how long a static point stays in view, roughly. Infinite
// for a still camera or an empty size.
double frames_to_cross_view(const Homography& h, cv::Size image);

// For how many frames the ground at `p` has been in view, assuming the camera kept this
// homography's motion: p carried back through h's inverse, frame by frame, until it leaves the
// image. Counts up to max_frames; max_frames + 1 means longer (or a still camera).
int frames_ground_in_view(const Homography& h, const cv::Point2d& p, cv::Size image, int max_frames);

// Mean transfer error ||H_a(p) - H_b(p)|| over a regular grid covering width x height.
double mean_transfer_error(const Homography& a, const Homography& b, int width, int height, int grid = 16);
// Transfer errors on that grid (for percentiles).
std::vector<double> transfer_errors(const Homography& a, const Homography& b, int width, int height, int grid = 16);

std::array<double, 9> to_row_major(const Homography& h);
Homography from_row_major(const std::array<double, 9>& values);

}  // namespace uavmot
