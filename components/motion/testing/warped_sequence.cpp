#include "warped_sequence.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <utility>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "uavmot/core/error.hpp"

namespace uavmot::motion::testing {
namespace {

// 3 x 3 mosaic of CLIF frames far enough apart to show different ground, in landscape.
cv::Mat load_mosaic(const std::string& folder) {
  std::vector<std::string> files;
  if (std::filesystem::is_directory(folder)) {
    for (const auto& entry : std::filesystem::directory_iterator(folder)) {
      if (entry.path().extension() == ".jpg") files.push_back(entry.path().string());
    }
  }
  std::sort(files.begin(), files.end());
  if (files.size() < 9) throw InputError(folder + ": expected the CLIF 2007 jpg frames, found " +
                                         std::to_string(files.size()));
  std::vector<cv::Mat> rows;
  for (int r = 0; r < 3; ++r) {
    std::vector<cv::Mat> tiles;
    for (int c = 0; c < 3; ++c) {
      const size_t index = static_cast<size_t>(r * 3 + c) * (files.size() - 1) / 8;
      cv::Mat tile = cv::imread(files[index], cv::IMREAD_GRAYSCALE);
      if (tile.empty()) throw InputError(files[index] + ": cannot read image");
      if (tile.rows > tile.cols) cv::transpose(tile, tile);
      tiles.push_back(tile);
    }
    cv::Mat row;
    cv::hconcat(tiles, row);
    rows.push_back(row);
  }
  cv::Mat mosaic;
  cv::vconcat(rows, mosaic);
  return mosaic;
}

cv::Mat make_patch_texture(cv::Size size, uint64_t seed) {
  // Blocks of random grey: corners inside the patch, like windows and roof edges of a car.
  cv::RNG rng(seed);
  cv::Mat texture(size, CV_8UC1);
  const int block = 4;
  for (int y = 0; y < size.height; y += block) {
    for (int x = 0; x < size.width; x += block) {
      const int value = rng.uniform(0, 2) ? rng.uniform(170, 255) : rng.uniform(0, 70);
      texture(cv::Rect(x, y, std::min(block, size.width - x), std::min(block, size.height - y))).setTo(value);
    }
  }
  return texture;
}

cv::Matx33d translation(double x, double y) { return {1, 0, x, 0, 1, y, 0, 0, 1}; }

}  // namespace

WarpedSequence::WarpedSequence(WarpedSequenceOptions options) : options_(std::move(options)) {
  ground_ = load_mosaic(options_.clif_folder);
  set_patches(options_.patches);
}

void WarpedSequence::set_patches(std::vector<Patch> patches) {
  options_.patches = std::move(patches);
  patch_textures_.clear();
  for (size_t i = 0; i < options_.patches.size(); ++i) {
    patch_textures_.push_back(make_patch_texture(options_.patches[i].size, options_.seed * 1000 + i + 1));
  }
}

Homography WarpedSequence::ground_to_frame(int k) const {
  const auto& o = options_;
  const double t = k - 1;
  const double heading = o.camera_heading_deg * M_PI / 180.0;
  // Camera centre on the ground: starts where the whole path stays inside the mosaic.
  const double travel = o.camera_speed_px * t;
  const cv::Point2d start(ground_.cols * 0.5 - std::cos(heading) * o.camera_speed_px * 40.0,
                          ground_.rows * 0.5 - std::sin(heading) * o.camera_speed_px * 40.0);
  const cv::Point2d centre(start.x + travel * std::cos(heading) + o.jitter_px * std::sin(0.31 * t),
                           start.y + travel * std::sin(heading) + o.jitter_px * std::cos(0.23 * t));
  const double angle = o.rotation_deg_per_frame * t * M_PI / 180.0;
  const double scale = std::pow(1.0 + o.zoom_per_frame, t);
  const double c = std::cos(angle) * scale, s = std::sin(angle) * scale;
  const cv::Matx33d rotate_scale(c, -s, 0, s, c, 0, 0, 0, 1);
  const double half = 0.5 * std::hypot(o.frame_size.width, o.frame_size.height);
  const cv::Matx33d tilt(1, 0, 0, 0, 1, 0, o.perspective * std::sin(0.05 * t) * 500.0 / half,
                         o.perspective * std::cos(0.04 * t) * 500.0 / half, 1);
  const cv::Matx33d g = translation((o.frame_size.width - 1) / 2.0, (o.frame_size.height - 1) / 2.0) * tilt *
                        rotate_scale * translation(-centre.x, -centre.y);
  Homography h = g;
  normalize_homography(h);
  return h;
}

Homography WarpedSequence::true_homography(int k) const {
  if (k <= 1) return Homography::eye();
  Homography h = ground_to_frame(k) * ground_to_frame(k - 1).inv();
  normalize_homography(h);
  return h;
}

cv::Point2d WarpedSequence::patch_corner(int patch, int k) const {
  const Patch& p = options_.patches[static_cast<size_t>(patch)];
  return {p.start.x + p.velocity[0] * (k - 1), p.start.y + p.velocity[1] * (k - 1)};
}

cv::Mat WarpedSequence::frame(int k) const {
  cv::Mat ground = ground_.clone();
  for (size_t i = 0; i < options_.patches.size(); ++i) {
    const cv::Point2d corner = patch_corner(static_cast<int>(i), k);
    const cv::Size size = options_.patches[i].size;
    const cv::Rect area =
        cv::Rect(static_cast<int>(std::floor(corner.x)) - 1, static_cast<int>(std::floor(corner.y)) - 1,
                 size.width + 3, size.height + 3) &
        cv::Rect(0, 0, ground.cols, ground.rows);
    if (area.empty()) continue;
    cv::Mat roi = ground(area);
    const cv::Matx23d shift(1, 0, corner.x - area.x, 0, 1, corner.y - area.y);
    cv::warpAffine(patch_textures_[i], roi, shift, roi.size(), cv::INTER_LINEAR, cv::BORDER_TRANSPARENT);
  }
  cv::Mat image;
  cv::warpPerspective(ground, image, cv::Mat(cv::Matx33d(ground_to_frame(k))), options_.frame_size, cv::INTER_LINEAR,
                      cv::BORDER_REFLECT_101);
  if (options_.noise_sigma > 0.0) {
    cv::Mat noise(image.size(), CV_16SC1);
    cv::RNG rng(options_.seed * 7919 + static_cast<uint64_t>(k));
    rng.fill(noise, cv::RNG::NORMAL, 0.0, options_.noise_sigma);
    cv::Mat sum;
    image.convertTo(sum, CV_16SC1);
    sum += noise;
    sum.convertTo(image, CV_8UC1);
  }
  return image;
}

int WarpedSequence::patch_at(int k, const cv::Point2d& p, double inner_margin, double outer_margin) const {
  const cv::Point2d g = apply_homography(ground_to_frame(k).inv(), p);
  int result = -1;
  for (size_t i = 0; i < options_.patches.size(); ++i) {
    const cv::Point2d c = patch_corner(static_cast<int>(i), k);
    const cv::Size size = options_.patches[i].size;
    const double margin = outer_margin;
    const bool inside_outer = g.x > c.x - 0.5 - margin && g.y > c.y - 0.5 - margin &&
                              g.x < c.x + size.width - 0.5 + margin && g.y < c.y + size.height - 0.5 + margin;
    if (!inside_outer) continue;
    const double inner = inner_margin;
    const bool inside_inner = g.x > c.x - 0.5 + inner && g.y > c.y - 0.5 + inner &&
                              g.x < c.x + size.width - 0.5 - inner && g.y < c.y + size.height - 0.5 - inner;
    if (!inside_inner) return -2;
    result = static_cast<int>(i);
  }
  return result;
}

cv::Vec2d WarpedSequence::relative_velocity(int patch, int k, const cv::Point2d& p) const {
  const Homography g = ground_to_frame(k);
  const cv::Point2d ground = apply_homography(g.inv(), p);
  return homography_jacobian(g, ground) * options_.patches[static_cast<size_t>(patch)].velocity;
}

std::vector<Patch> scatter_patches(const WarpedSequence& sequence, int middle, int moving, int parked,
                                   double min_speed, double max_speed, uint64_t seed) {
  std::vector<Patch> patches;
  cv::RNG rng(seed);
  const cv::Size frame = sequence.options().frame_size;
  const int total = moving + parked;
  const int cols = std::max(1, static_cast<int>(std::ceil(std::sqrt(total * 16.0 / 9.0))));
  const int rows = (total + cols - 1) / cols;
  const Homography frame_to_ground = sequence.ground_to_frame(middle).inv();
  for (int i = 0; i < total; ++i) {
    const int r = i / cols, c = i % cols;
    const cv::Point2d in_frame((0.1 + 0.8 * (c + 0.5) / cols) * frame.width + rng.uniform(-6.0, 6.0),
                               (0.1 + 0.8 * (r + 0.5) / rows) * frame.height + rng.uniform(-6.0, 6.0));
    Patch p;
    if (i < moving) {
      const double speed = min_speed + (max_speed - min_speed) * (moving > 1 ? i / (moving - 1.0) : 0.0);
      const double direction = rng.uniform(0.0, 2.0 * M_PI);
      p.velocity = cv::Vec2d(speed * std::cos(direction), speed * std::sin(direction));
    }
    const cv::Point2d ground = apply_homography(frame_to_ground, in_frame);
    p.start = cv::Point2d(ground.x - p.velocity[0] * (middle - 1), ground.y - p.velocity[1] * (middle - 1));
    patches.push_back(p);
  }
  return patches;
}

}  // namespace uavmot::motion::testing
