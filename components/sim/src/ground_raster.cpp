#include "ground_raster.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <random>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "uavmot/core/error.hpp"

namespace uavmot::sim::detail {
namespace {
namespace fs = std::filesystem;

std::vector<std::string> list_images(const std::string& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw InputError("ground.texture_dir '" + dir + "' is not a readable folder");
  std::vector<std::string> files;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    std::string ext = entry.path().extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (ext == ".jpg" || ext == ".jpeg" || ext == ".png" || ext == ".tif" || ext == ".tiff" || ext == ".bmp")
      files.push_back(entry.path().string());
  }
  std::sort(files.begin(), files.end());  // directory order is not defined
  if (files.empty()) throw InputError("ground.texture_dir '" + dir + "' holds no .jpg/.png/.tif/.bmp image");
  return files;
}

// A smooth random field: fallback ground without imagery, and asphalt wear.
cv::Mat smooth_noise(cv::Size size, double sigma_px, double amplitude, uint64_t seed) {
  cv::RNG rng(seed);
  const double shrink = std::max(1.0, sigma_px / 2.0);
  const cv::Size small(std::max(2, static_cast<int>(size.width / shrink)), std::max(2, static_cast<int>(size.height / shrink)));
  cv::Mat noise(small, CV_32F);
  rng.fill(noise, cv::RNG::NORMAL, 0.0, 1.0);
  cv::GaussianBlur(noise, noise, cv::Size(), 2.0);
  cv::Scalar mean, stddev;
  cv::meanStdDev(noise, mean, stddev);
  noise = (noise - mean[0]) * (amplitude / std::max(1e-6, stddev[0]));
  cv::Mat out;
  cv::resize(noise, out, size, 0, 0, cv::INTER_LINEAR);
  return out;
}

// Mosaic of feathered tiles at the texture's own resolution, covering size_px.
cv::Mat texture_mosaic(const Scenario& scenario, cv::Size size_px, uint64_t seed) {
  const GroundParams& g = scenario.ground;
  if (g.texture_dir == "procedural") {
    cv::Mat base = smooth_noise(size_px, 40.0, 25.0, seed) + smooth_noise(size_px, 4.0, 10.0, seed + 1) + 110.0;
    return base;
  }
  const std::vector<std::string> files = list_images(g.texture_dir.empty() ? default_texture_dir() : g.texture_dir);
  std::mt19937_64 rng(seed ^ 0x7E87ULL);
  std::map<size_t, cv::Mat> cache;
  const auto load = [&](size_t index) -> const cv::Mat& {
    auto it = cache.find(index);
    if (it != cache.end()) return it->second;
    cv::Mat img = cv::imread(files[index], cv::IMREAD_GRAYSCALE);
    if (img.empty() || img.cols < 32 || img.rows < 32) throw InputError("cannot read texture image '" + files[index] + "'");
    cv::Mat f;
    img.convertTo(f, CV_32F);
    // Normalise every tile to the same mean and spread so seams do not show as steps.
    cv::Scalar mean, stddev;
    cv::meanStdDev(f, mean, stddev);
    f = (f - mean[0]) * (38.0 / std::max(1.0, stddev[0])) + 115.0;
    return cache.emplace(index, f).first->second;
  };
  const cv::Mat& first = load(0);
  const int overlap = std::max(8, std::min(first.cols, first.rows) / 8);
  const int step_x = first.cols - overlap, step_y = first.rows - overlap;
  cv::Mat acc = cv::Mat::zeros(size_px, CV_32F), weight = cv::Mat::zeros(size_px, CV_32F);
  std::uniform_int_distribution<size_t> pick(0, files.size() - 1);
  for (int y0 = -overlap; y0 < size_px.height; y0 += step_y) {
    for (int x0 = -overlap; x0 < size_px.width; x0 += step_x) {
      cv::Mat tile = load(pick(rng)).clone();
      if (rng() % 2) cv::flip(tile, tile, -1);  // 180-degree turn keeps the look of nadir imagery
      if (tile.size() != first.size()) cv::resize(tile, tile, first.size());
      // Feathering weight: a ramp over the overlap at each edge.
      cv::Mat w(tile.size(), CV_32F);
      for (int y = 0; y < w.rows; ++y) {
        const float wy = std::min(1.0f, static_cast<float>(std::min(y + 1, w.rows - y)) / overlap);
        float* row = w.ptr<float>(y);
        for (int x = 0; x < w.cols; ++x) row[x] = wy * std::min(1.0f, static_cast<float>(std::min(x + 1, w.cols - x)) / overlap);
      }
      const cv::Rect dst = cv::Rect(x0, y0, tile.cols, tile.rows) & cv::Rect(0, 0, size_px.width, size_px.height);
      if (dst.empty()) continue;
      const cv::Rect src(dst.x - x0, dst.y - y0, dst.width, dst.height);
      cv::Mat weighted;
      cv::multiply(tile(src), w(src), weighted);
      acc(dst) += weighted;
      weight(dst) += w(src);
    }
  }
  cv::Mat out;
  cv::divide(acc, cv::max(weight, 1e-3), out);
  return out;
}

// Draws into a coverage mask with anti-aliasing, then blends `gray` through it.
class Painter {
 public:
  Painter(cv::Mat& image, const cv::Matx33d& raster_from_world) : image_(image), to_raster_(raster_from_world) {
    mask_ = cv::Mat::zeros(image.size(), CV_8U);
  }
  cv::Point to_px(cv::Point2d world) const {
    const cv::Vec3d p = to_raster_ * cv::Vec3d(world.x, world.y, 1.0);
    return {static_cast<int>(std::lround(p[0] / p[2] * 16.0)), static_cast<int>(std::lround(p[1] / p[2] * 16.0))};
  }
  double scale() const { return to_raster_(0, 0); }
  void polyline(const std::vector<cv::Point2d>& world, double width_m) {
    std::vector<cv::Point> px;
    px.reserve(world.size());
    for (const auto& w : world) px.push_back(to_px(w));
    const double width_px = width_m * scale();
    const int thickness = std::max(1, static_cast<int>(std::lround(width_px)));
    cv::polylines(mask_, px, false, cv::Scalar(255), thickness, cv::LINE_AA, 4);
    grow(px, thickness);
    alpha_scale_ = std::min(1.0, width_px);  // lines thinner than a pixel blend proportionally
  }
  void polygon(const std::vector<cv::Point2d>& world) {
    std::vector<cv::Point> px;
    for (const auto& w : world) px.push_back(to_px(w));
    cv::fillConvexPoly(mask_, px, cv::Scalar(255), cv::LINE_AA, 4);
    grow(px, 1);
    alpha_scale_ = 1.0;
  }
  // image = image * (1 - a) + value * a with a = mask * opacity; value may vary per pixel.
  void blend(const cv::Mat& value, double opacity) {
    const cv::Rect roi = take_roi();
    if (roi.empty()) return;
    cv::Mat a;
    mask_(roi).convertTo(a, CV_32F, opacity * alpha_scale_ / 255.0);
    cv::Mat blended = image_(roi).mul(1.0 - a) + value(roi).mul(a);
    blended.copyTo(image_(roi));
    mask_(roi).setTo(0);
  }
  void blend(double value, double opacity) {
    const cv::Rect roi = take_roi();
    if (roi.empty()) return;
    cv::Mat a;
    mask_(roi).convertTo(a, CV_32F, opacity * alpha_scale_ / 255.0);
    cv::Mat blended = image_(roi).mul(1.0 - a) + a * value;
    blended.copyTo(image_(roi));
    mask_(roi).setTo(0);
  }

 private:
  void grow(const std::vector<cv::Point>& px16, int thickness) {
    for (const cv::Point& p : px16) {
      const cv::Rect r(p.x / 16 - thickness - 2, p.y / 16 - thickness - 2, 2 * thickness + 5, 2 * thickness + 5);
      roi_ = roi_.empty() ? r : (roi_ | r);
    }
  }
  cv::Rect take_roi() {
    const cv::Rect roi = roi_ & cv::Rect(0, 0, mask_.cols, mask_.rows);
    roi_ = cv::Rect();
    return roi;
  }

  cv::Mat& image_;
  cv::Matx33d to_raster_;
  cv::Rect roi_;
  cv::Mat mask_;
  double alpha_scale_ = 1.0;
};

std::vector<cv::Point2d> offset_line(const Road& road, double offset, double s0, double s1) {
  std::vector<cv::Point2d> pts;
  for (double s = s0; s <= s1 + 1e-9; s += 0.5) {
    const cv::Point2d t = road.tangent_at(s);
    pts.push_back(road.point_at(s) + cv::Point2d(-t.y, t.x) * offset);
  }
  return pts;
}

// Stretches of the road that are not inside a crossing (markings stop at junctions).
std::vector<std::pair<double, double>> marking_spans(const RoadNetwork& net, int r) {
  std::vector<std::pair<double, double>> blocked;
  for (const Crossing& x : net.crossings) {
    if (x.road_a == r) blocked.push_back({x.s_a - net.roads[x.road_b].half_width() - 1.0, x.s_a + net.roads[x.road_b].half_width() + 1.0});
    if (x.road_b == r) blocked.push_back({x.s_b - net.roads[x.road_a].half_width() - 1.0, x.s_b + net.roads[x.road_a].half_width() + 1.0});
  }
  std::sort(blocked.begin(), blocked.end());
  std::vector<std::pair<double, double>> spans;
  double start = 0.0;
  for (const auto& b : blocked) {
    if (b.first > start) spans.push_back({start, b.first});
    start = std::max(start, b.second);
  }
  if (start < net.roads[r].length()) spans.push_back({start, net.roads[r].length()});
  return spans;
}

void paint_roads(cv::Mat& raster, const GroundRaster& geo, const Scenario& scenario, const RoadNetwork& net, uint64_t seed) {
  const RoadParams& p = scenario.roads;
  const cv::Matx33d raster_from_world = geo.world_from_raster().inv();
  Painter painter(raster, raster_from_world);
  // Asphalt with low-frequency wear, keeping a little of the underlying texture.
  cv::Mat asphalt = smooth_noise(raster.size(), 6.0 / geo.gsd_m, 6.0, seed ^ 0xA5F) + p.asphalt_gray;
  cv::Mat texture_detail;
  cv::GaussianBlur(raster, texture_detail, cv::Size(), 3.0);
  texture_detail = (raster - texture_detail) * 0.35;
  asphalt += texture_detail;
  for (const Road& road : net.roads) {
    painter.polyline(road.points, 2.0 * road.half_width());
    painter.blend(asphalt, p.asphalt_opacity);
  }
  for (const auto& lot : net.lots) {
    const cv::Point2d a(std::cos(lot.angle_rad), std::sin(lot.angle_rad)), c(-a.y, a.x);
    const cv::Point2d h = a * (lot.along_m / 2.0), v = c * (lot.across_m / 2.0 + 2.0);
    painter.polygon({lot.centre_m - h - v, lot.centre_m + h - v, lot.centre_m + h + v, lot.centre_m - h + v});
    painter.blend(asphalt, p.asphalt_opacity);
    // Stall lines.
    for (int k = 0; k <= 14; ++k) {
      for (int row = 0; row < 2; ++row) {
        const cv::Point2d base = lot.centre_m + a * ((k - 7.0) * 2.7) + c * ((row - 0.5) * 10.0);
        painter.polyline({base - c * 2.5, base + c * 2.5}, p.marking_width_m * 0.8);
        painter.blend(p.marking_gray * 0.85, 0.8);
      }
    }
  }
  if (p.marking_width_m <= 0.0) return;
  for (size_t r = 0; r < net.roads.size(); ++r) {
    const Road& road = net.roads[r];
    const int n = road.lanes_per_direction;
    for (const auto& span : marking_spans(net, static_cast<int>(r))) {
      if (span.second - span.first < 1.0) continue;
      // Edge lines and the centre line, solid.
      for (double off : {-n * road.lane_width_m, 0.0, n * road.lane_width_m}) {
        painter.polyline(offset_line(road, off, span.first, span.second), p.marking_width_m);
        painter.blend(p.marking_gray, 0.9);
      }
      // Dashed lines between lanes of one direction.
      for (int k = 1; k < n; ++k) {
        for (double sign : {-1.0, 1.0}) {
          const double off = sign * k * road.lane_width_m;
          for (double s = span.first; s < span.second; s += p.dash_length_m + p.dash_gap_m) {
            painter.polyline(offset_line(road, off, s, std::min(span.second, s + p.dash_length_m)), p.marking_width_m);
          }
          painter.blend(p.marking_gray, 0.9);
        }
      }
    }
  }
}

}  // namespace

cv::Size checked_raster_size(const Scenario& scenario, cv::Rect2d region, double raster_gsd) {
  const double width = std::ceil(region.width / raster_gsd) + 1.0, height = std::ceil(region.height / raster_gsd) + 1.0;
  const double megapixels = width * height / 1e6;
  if (!(megapixels <= scenario.ground.raster_max_megapixels))
    throw InputError("scenario '" + scenario.name + "' needs a ground raster of " + std::to_string(static_cast<int64_t>(width)) +
                     " x " + std::to_string(static_cast<int64_t>(height)) + " px (" + std::to_string(static_cast<int64_t>(megapixels)) +
                     " MP), more than ground.raster_max_megapixels = " + std::to_string(scenario.ground.raster_max_megapixels) +
                     "; use fewer frames or a slower camera");
  return {static_cast<int>(width), static_cast<int>(height)};
}

GroundRaster build_ground_raster(const Scenario& scenario, const RoadNetwork& network, cv::Rect2d region, double raster_gsd,
                                 uint64_t seed) {
  GroundRaster ground;
  ground.gsd_m = raster_gsd;
  ground.origin_m = {region.x, region.y};
  const cv::Size size = checked_raster_size(scenario, region, raster_gsd);
  // The mosaic at the texture's resolution, then resampled to the raster.
  const double texture_gsd = scenario.ground.texture_gsd_m;
  const cv::Size texture_size(std::max(2, static_cast<int>(std::ceil(region.width / texture_gsd)) + 2),
                              std::max(2, static_cast<int>(std::ceil(region.height / texture_gsd)) + 2));
  cv::Mat mosaic = texture_mosaic(scenario, texture_size, seed);
  if (scenario.ground.texture_contrast != 1.0) {
    const double mean = cv::mean(mosaic)[0];
    mosaic = (mosaic - mean) * scenario.ground.texture_contrast + mean;
  }
  // Raster pixel (i, j) sits at world origin + (i, j) * raster_gsd, i.e. mosaic px (i, j) * raster_gsd / texture_gsd.
  cv::Mat raster;
  const cv::Matx23d mosaic_from_raster(raster_gsd / texture_gsd, 0, 0, 0, raster_gsd / texture_gsd, 0);
  cv::warpAffine(mosaic, raster, mosaic_from_raster, size, cv::INTER_CUBIC | cv::WARP_INVERSE_MAP, cv::BORDER_REFLECT);
  // Upsampled imagery is smooth; real ground at this resolution has grain (gravel, grass, roof texture).
  if (scenario.ground.detail_noise > 0.0) raster += smooth_noise(size, 1.2, scenario.ground.detail_noise, seed ^ 0xD37A11ULL);
  paint_roads(raster, ground, scenario, network, seed);
  raster.convertTo(ground.image, CV_8U);
  return ground;
}

}  // namespace uavmot::sim::detail
