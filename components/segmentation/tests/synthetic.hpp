#pragma once
// Synthetic images and features with known answers for the segmentation tests and benchmark.

#include <cmath>
#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "uavmot/core/chain_types.hpp"

namespace uavmot::segmentation::testing {

// Low-contrast aerial-like background: smooth blotches (+-amplitude) plus pixel noise.
inline cv::Mat textured_background(cv::Size size, double mean, double amplitude, double noise_sigma, uint64_t seed) {
  cv::RNG rng(seed);
  cv::Mat coarse(size.height / 8 + 2, size.width / 8 + 2, CV_32F);
  rng.fill(coarse, cv::RNG::UNIFORM, -amplitude, amplitude);
  cv::Mat smooth;
  cv::resize(coarse, smooth, cv::Size(size.width + 16, size.height + 16), 0, 0, cv::INTER_CUBIC);
  smooth = smooth(cv::Rect(8, 8, size.width, size.height)).clone();
  cv::Mat noise(size, CV_32F);
  rng.fill(noise, cv::RNG::NORMAL, 0.0, noise_sigma);
  cv::Mat image;
  cv::Mat(smooth + noise + mean).convertTo(image, CV_8U);
  return image;
}

// A car-like object: every pixel whose centre lies inside the oriented box gets `value`
// (exact sampling; cv::fillConvexPoly also fills pixels its outline touches, about half a pixel
// too many on every side).
inline void draw_car(cv::Mat& image, const OrientedBox& box, double value) {
  const cv::Rect2d bounds = axis_aligned_bounds(box);
  for (int y = std::max(0, static_cast<int>(std::floor(bounds.y))); y <= std::min(image.rows - 1, static_cast<int>(std::ceil(bounds.y + bounds.height))); ++y) {
    for (int x = std::max(0, static_cast<int>(std::floor(bounds.x))); x <= std::min(image.cols - 1, static_cast<int>(std::ceil(bounds.x + bounds.width))); ++x) {
      if (box_contains(box, cv::Point2d(x, y))) image.at<uchar>(y, x) = cv::saturate_cast<uchar>(value);
    }
  }
}

// Moving features on an object: its four corners pulled in by `inset` px, and its centre.
inline std::vector<TrackedFeature> features_on(const OrientedBox& box, cv::Vec2d velocity, uint64_t first_id,
                                               double inset = 1.0) {
  OrientedBox inner = box;
  inner.length -= 2.0 * inset;
  inner.width -= 2.0 * inset;
  std::vector<cv::Point2d> points;
  for (const auto& c : box_corners(inner)) points.push_back(c);
  points.emplace_back(box.cx, box.cy);
  std::vector<TrackedFeature> out;
  for (const auto& p : points) {
    TrackedFeature f;
    f.id = first_id++;
    f.position = p;
    f.velocity = velocity;
    f.velocity_sigma = 0.05;
    f.age = 10;
    f.moving = true;
    out.push_back(f);
  }
  return out;
}

}  // namespace uavmot::segmentation::testing
