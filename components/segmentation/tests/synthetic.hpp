#pragma once
// Synthetic images and features with known answers for the segmentation tests and benchmark.

#include <cmath>
#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "uavmot/core/chain_types.hpp"
#include "uavmot/core/homography.hpp"

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

inline Homography translation(double dx, double dy) { return Homography(1, 0, dx, 0, 1, dy, 0, 0, 1); }

// `image` shifted by (dx, dy): out(x) = image(x - d), bilinear.
inline cv::Mat shifted(const cv::Mat& image, double dx, double dy) {
  cv::Mat out;
  cv::warpAffine(image, out, cv::Matx23d(1, 0, dx, 0, 1, dy), image.size(), cv::INTER_LINEAR, cv::BORDER_REFLECT);
  return out;
}

// Two frames of a camera moving by (3, 3) px over textured ground, with a textured 15 x 6 px car
// (paint of mean grey `paint_mean`) driving by `velocity` relative to the ground.
struct TwoFrames {
  cv::Mat previous, current;
  OrientedBox car;   // inside the car in the current frame, a pixel in from its outline
  OrientedBox body;  // the car's outline in the current frame
};

inline TwoFrames two_frames(cv::Vec2d velocity, double paint_mean = 150.0) {
  const cv::Mat ground = textured_background(cv::Size(200, 160), 100.0, 40.0, 0.0, 7);
  const cv::Mat paint = textured_background(cv::Size(200, 160), paint_mean, 60.0, 0.0, 8);
  const cv::Rect car_then(90, 70, 15, 6);
  TwoFrames f;
  f.previous = ground.clone();
  paint(car_then).copyTo(f.previous(car_then));
  f.current = shifted(f.previous, 3.0 + velocity[0], 3.0 + velocity[1]);  // the car, moved with camera and velocity
  cv::Mat ground_now = shifted(ground, 3.0, 3.0);
  cv::Mat car_mask = cv::Mat::zeros(ground.size(), CV_8U);
  car_mask(car_then).setTo(255);
  ground_now.copyTo(f.current, shifted(car_mask, 3.0 + velocity[0], 3.0 + velocity[1]) < 128);
  // Pixel centres at integer coordinates: the car's pixels 90..104 and 70..75 are centred on 97 and 72.5.
  const double cx = car_then.x + 7.0 + 3.0 + velocity[0], cy = car_then.y + 2.5 + 3.0 + velocity[1];
  f.car = {cx, cy, 4.0, 13.0, 0.0};
  f.body = {cx, cy, 6.0, 15.0, 0.0};
  return f;
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
