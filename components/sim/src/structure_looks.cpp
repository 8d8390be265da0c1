#include "structure_looks.hpp"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

namespace uavmot::sim::detail {
namespace {

int texels(double metres) { return std::max(2, static_cast<int>(std::ceil(metres / kStructureTexelM))); }

// Gaussian noise smoothed over `sigma` texels, scaled to `amplitude` gray levels of spread.
cv::Mat noise(cv::Size size, double sigma, double amplitude, cv::RNG& rng) {
  cv::Mat n(size, CV_32F);
  rng.fill(n, cv::RNG::NORMAL, 0.0, 1.0);
  if (sigma > 0.0) cv::GaussianBlur(n, n, cv::Size(), sigma, sigma, cv::BORDER_REFLECT);
  cv::Scalar mean, stddev;
  cv::meanStdDev(n, mean, stddev);
  return (n - mean[0]) * (amplitude / std::max(1e-6, stddev[0]));
}

cv::Rect texel_rect(double x_m, double y_m, double w_m, double h_m) {
  return {static_cast<int>(x_m / kStructureTexelM), static_cast<int>(y_m / kStructureTexelM), texels(w_m), texels(h_m)};
}

}  // namespace

cv::Mat roof_texture(const Structure& s) {
  cv::RNG rng(s.look_seed);
  const cv::Size size(texels(s.length_m), texels(s.width_m));
  const bool wall = s.kind == StructureKind::Wall;
  const double albedo = wall ? rng.uniform(130.0, 170.0) : rng.uniform(85.0, 190.0);
  cv::Mat roof = noise(size, 8.0, 7.0, rng) + noise(size, 1.0, 6.0, rng) + albedo;
  if (wall) return roof;
  const cv::Rect all(0, 0, size.width, size.height);
  // A parapet: a band darker or lighter than the roof at its edge.
  const int rim = texels(0.5);
  const double rim_gray = albedo + (rng.uniform(0.0, 1.0) < 0.5 ? -35.0 : 35.0);
  for (const cv::Rect band : {cv::Rect(0, 0, size.width, rim), cv::Rect(0, size.height - rim, size.width, rim),
                              cv::Rect(0, 0, rim, size.height), cv::Rect(size.width - rim, 0, rim, size.height)})
    roof(band & all).setTo(rim_gray);
  // Rooftop units (air handling, stair houses, skylights) with a shadow on one side.
  const int units = 1 + static_cast<int>(rng.uniform(0, 3 + static_cast<int>(s.length_m * s.width_m / 150.0)));
  for (int k = 0; k < units; ++k) {
    const double w = rng.uniform(1.2, std::max(1.3, std::min(4.5, s.length_m / 3.0)));
    const double h = rng.uniform(1.2, std::max(1.3, std::min(4.5, s.width_m / 3.0)));
    const double x = rng.uniform(1.0, std::max(1.1, s.length_m - w - 1.0));
    const double y = rng.uniform(1.0, std::max(1.1, s.width_m - h - 1.0));
    const double gray = std::clamp(albedo + (rng.uniform(0.0, 1.0) < 0.6 ? 55.0 : -50.0), 20.0, 240.0);
    roof(texel_rect(x + 0.3, y + 0.3, w, h) & all) *= 0.55;  // shadow, offset away from the sun
    roof(texel_rect(x, y, w, h) & all).setTo(gray);
  }
  return roof;
}

cv::Mat facade_texture(const Structure& s, double length_m, double gain, int side) {
  cv::RNG rng(s.look_seed + 101ULL * static_cast<uint64_t>(side + 1));
  const cv::Size size(texels(length_m), texels(s.height_m));
  cv::RNG colour(s.look_seed + 7ULL);  // all sides of one structure share the facade colour
  const double albedo = colour.uniform(110.0, 200.0);
  cv::Mat face = noise(size, 2.0, 6.0, rng) + noise(size, 0.8, 5.0, rng) + albedo;
  const cv::Rect all(0, 0, size.width, size.height);
  if (s.kind == StructureKind::Wall) {
    // Panel joints every 2.5 m.
    for (double x = 2.5; x < length_m; x += 2.5) face(texel_rect(x, 0.0, 0.12, s.height_m) & all) *= 0.6;
  } else {
    // Windows: rows per 3 m floor, columns 2.5-3.5 m apart.
    const double spacing = colour.uniform(2.5, 3.5), window_w = colour.uniform(1.0, 1.6), window_h = colour.uniform(1.2, 1.7);
    const double window_gray = colour.uniform(35.0, 70.0);
    for (double floor_top = 0.8; floor_top + window_h < s.height_m - 0.5; floor_top += 3.0)
      for (double x = std::fmod(length_m, spacing) / 2.0 + (spacing - window_w) / 2.0; x + window_w < length_m; x += spacing)
        face(texel_rect(x, floor_top, window_w, window_h) & all).setTo(window_gray + rng.uniform(-8.0, 8.0));
  }
  return face * gain;
}

cv::Mat canopy_texture(const Structure& s, cv::Point2d sun) {
  cv::RNG rng(s.look_seed);
  const int n = texels(2.0 * s.canopy_radius_m);
  const cv::Size size(n, n);
  const double base = rng.uniform(50.0, 78.0);
  // Leaves: strong texel-scale grain over clumps of foliage.
  cv::Mat canopy = noise(size, 0.7, 16.0, rng) + noise(size, 3.0, 14.0, rng) + base;
  // Rounded crown: lit toward the sun, darker toward its rim.
  for (int y = 0; y < n; ++y) {
    float* row = canopy.ptr<float>(y);
    for (int x = 0; x < n; ++x) {
      const double u = (x + 0.5) / n * 2.0 - 1.0, v = (y + 0.5) / n * 2.0 - 1.0;
      const double r2 = std::min(1.0, u * u + v * v);
      row[x] = static_cast<float>(row[x] * (1.0 - 0.35 * r2) + 14.0 * (u * sun.x + v * sun.y));
    }
  }
  return canopy;
}

}  // namespace uavmot::sim::detail
