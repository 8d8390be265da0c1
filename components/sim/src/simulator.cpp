#include "uavmot/sim/simulator.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "camera_path.hpp"
#include "ground_raster.hpp"
#include "road_network.hpp"
#include "structure_layout.hpp"
#include "structure_renderer.hpp"
#include "traffic.hpp"
#include "uavmot/core/error.hpp"
#include "vehicle_renderer.hpp"

namespace uavmot::sim {
namespace {
constexpr double kPi = 3.14159265358979323846;

cv::Matx33d normalized(const cv::Matx33d& h) { return h * (1.0 / h(2, 2)); }

struct ViewArea {
  cv::Rect2d region_m;     // everything any frame sees, with margin
  cv::Point2d centre_m;    // middle of the seen area
  double radius_m = 0.0;   // from the centre to the farthest seen point
  double min_gsd_m = 0.0;
};

// Image points whose ground positions bound the view. A nadir camera sees a near-square
// footprint whose extremes are the corners; a pitched one also needs the edge midpoints (the
// finest GSD is at the middle of the near edge). Nadir keeps exactly the corners so flat
// presets render as before.
std::vector<cv::Point2d> view_samples(const Scenario& s) {
  std::vector<double> steps{-0.5, 0.5};
  if (s.camera.pitch_deg != 0.0) steps = {-0.5, -0.25, 0.0, 0.25, 0.5};
  std::vector<cv::Point2d> samples;
  for (double fx : steps)
    for (double fy : steps)
      samples.emplace_back((s.camera.width - 1) / 2.0 + fx * (s.camera.width + 8), (s.camera.height - 1) / 2.0 + fy * (s.camera.height + 8));
  return samples;
}

// Metres per pixel of the ground at image point p through g, in the finest direction for a
// pitched camera (the raster must resolve that), by area for nadir (as before).
double ground_gsd(const cv::Matx33d& g, cv::Point2d world, bool pitched) {
  const cv::Matx22d j = homography_jacobian(g, world);
  if (!pitched) return 1.0 / std::sqrt(std::abs(cv::determinant(j)));
  cv::Mat singular;
  cv::SVD::compute(cv::Mat(j), singular, cv::SVD::NO_UV);
  return 1.0 / singular.at<double>(0);  // px per metre along the best-resolved direction
}

ViewArea view_area(const detail::CameraPath& camera, const Scenario& s) {
  ViewArea area;
  std::vector<cv::Point2d> corners;
  const double dt = 1.0 / s.fps;
  const int samples = std::min(s.frames, 200);
  const std::vector<cv::Point2d> image_points = view_samples(s);
  const bool pitched = s.camera.pitch_deg != 0.0;
  area.min_gsd_m = 1e300;
  for (int i = 0; i <= samples; ++i) {
    const double t = (s.frames - 1) * dt * i / std::max(1, samples);
    const cv::Matx33d world_from_image = camera.image_from_world(t).inv();
    const size_t first = corners.size();
    for (const cv::Point2d& img : image_points) corners.push_back(apply_homography(world_from_image, img));
    // Finest ground resolution seen anywhere in the image (tilt makes it vary).
    const cv::Matx33d g = camera.image_from_world(t);
    for (size_t k = corners.size(); k-- > first;) area.min_gsd_m = std::min(area.min_gsd_m, ground_gsd(g, corners[k], pitched));
  }
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  for (const auto& c : corners) {
    x0 = std::min(x0, c.x);
    y0 = std::min(y0, c.y);
    x1 = std::max(x1, c.x);
    y1 = std::max(y1, c.y);
  }
  const double margin = 20.0;
  area.region_m = cv::Rect2d(x0 - margin, y0 - margin, x1 - x0 + 2 * margin, y1 - y0 + 2 * margin);
  area.centre_m = {(x0 + x1) / 2.0, (y0 + y1) / 2.0};
  for (const auto& c : corners) area.radius_m = std::max(area.radius_m, cv::norm(c - area.centre_m));
  detail::checked_raster_size(s, area.region_m, area.min_gsd_m);  // fail early, before building roads
  return area;
}

// Adds each id's pixel count in the mask to pixels[id].first (or .second).
void count_pixels(const cv::Mat& mask, std::map<int, std::pair<int64_t, int64_t>>& pixels, bool second) {
  for (int y = 0; y < mask.rows; ++y) {
    const int32_t* row = mask.ptr<int32_t>(y);
    for (int x = 0; x < mask.cols; ++x) {
      if (row[x] == 0) continue;
      auto& count = pixels[row[x]];
      ++(second ? count.second : count.first);
    }
  }
}

}  // namespace

class Simulator::Impl {
 public:
  Impl(Scenario scenario, uint64_t seed)
      : scenario_((validate_scenario(scenario), std::move(scenario))),
        seed_(seed),
        camera_(scenario_.camera, seed),
        area_(view_area(camera_, scenario_)),
        network_(detail::make_road_network(scenario_, area_.centre_m, area_.radius_m + 40.0, area_.radius_m, seed)),
        ground_(detail::build_ground_raster(scenario_, network_, area_.region_m, area_.min_gsd_m, seed)),
        traffic_(scenario_, network_, area_.centre_m, area_.radius_m, seed),
        structures_(detail::place_structures(scenario_, network_, area_.region_m, seed), scenario_.structures) {
    const double dt = 1.0 / scenario_.fps;
    const int warmup_steps = static_cast<int>(std::lround(scenario_.traffic.warmup_s * scenario_.fps));
    for (int i = 0; i < warmup_steps; ++i) traffic_.step(dt);
    const cv::Point2d image_centre((scenario_.camera.width - 1) / 2.0, (scenario_.camera.height - 1) / 2.0);
    traffic_.add_scripted(apply_homography(camera_.image_from_world(0.0).inv(), image_centre));
    const double a = scenario_.traffic.shadow_angle_deg * kPi / 180.0;
    shadow_.offset_m = cv::Point2d(std::cos(a), std::sin(a)) * scenario_.traffic.shadow_length_m;
    shadow_.strength = scenario_.traffic.shadow_strength;
  }

  bool next(SimFrame& frame);

  Scenario scenario_;
  uint64_t seed_;
  detail::CameraPath camera_;
  ViewArea area_;
  detail::RoadNetwork network_;
  detail::GroundRaster ground_;
  detail::Traffic traffic_;
  detail::ShadowParams shadow_;
  detail::StructureRenderer structures_;
  int64_t index_ = 0;  // frames produced
  cv::Matx33d previous_image_from_world_;
  std::map<int, int> public_ids_;  // internal id -> id in the output
  std::set<int> moving_ids_;
  std::set<int> parked_ids_;
};

bool Simulator::Impl::next(SimFrame& frame) {
  if (index_ >= scenario_.frames) return false;
  const double dt = 1.0 / scenario_.fps;
  const double t = static_cast<double>(index_) * dt;
  const cv::Size size(scenario_.camera.width, scenario_.camera.height);
  const cv::Matx33d image_from_world = camera_.image_from_world(t);
  const cv::Matx33d image_from_raster = normalized(image_from_world * ground_.world_from_raster());

  // Background: the ground raster seen through this frame's homography.
  cv::Mat background;
  cv::warpPerspective(ground_.image, background, cv::Mat(image_from_raster), size, cv::INTER_LINEAR, cv::BORDER_REFLECT);
  cv::Mat canvas;
  background.convertTo(canvas, CV_32F);

  // Vehicles at least partly inside the image, in internal-id order.
  const OrientedBox image_rect{(size.width - 1) / 2.0, (size.height - 1) / 2.0, static_cast<double>(size.height),
                               static_cast<double>(size.width), 0.0};
  std::vector<std::pair<int, const detail::Vehicle*>> visible;
  std::map<int, std::pair<OrientedBox, double>> boxes;
  for (const detail::Vehicle& v : traffic_.vehicles()) {
    const OrientedBox box = detail::image_box(v, image_from_world);
    const cv::Rect2d bounds = axis_aligned_bounds(box);
    if (bounds.x > size.width || bounds.y > size.height || bounds.x + bounds.width < -1 || bounds.y + bounds.height < -1) continue;
    const double visibility = std::min(1.0, intersection_area(box, image_rect) / std::max(1e-9, box_area(box)));
    if (visibility <= 0.0) continue;
    visible.push_back({v.internal_id, &v});
    boxes[v.internal_id] = {box, visibility};
  }
  std::sort(visible.begin(), visible.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<const detail::Vehicle*> drawn;
  std::vector<int> ids;
  for (const auto& [internal, v] : visible) {
    auto it = public_ids_.find(internal);
    if (it == public_ids_.end()) it = public_ids_.emplace(internal, static_cast<int>(public_ids_.size()) + 1).first;
    drawn.push_back(v);
    ids.push_back(it->second);
  }
  // A fresh buffer each frame: callers keep SimFrame copies (cv::Mat copies share data).
  frame.object_id_mask = cv::Mat(size, CV_32S, cv::Scalar(0));
  detail::render_vehicles(canvas, frame.object_id_mask, drawn, ids, image_from_world, shadow_);
  // Structures stand in front of the ground and of every vehicle (vehicles are flat on the
  // ground and never inside a structure), so they are drawn last and hide what is behind.
  std::map<int, std::pair<int64_t, int64_t>> pixels;  // id -> (drawn, still seen)
  frame.structures.clear();
  if (!structures_.empty()) {
    count_pixels(frame.object_id_mask, pixels, false);
    frame.structures = structures_.render(canvas, frame.object_id_mask, camera_.projection(t), camera_.centre(t));
    count_pixels(frame.object_id_mask, pixels, true);
  }

  // Sensor: gain drift and contrast, optics blur, noise, 8-bit quantisation, JPEG.
  const SensorParams& sensor = scenario_.sensor;
  const double gain = sensor.contrast * (1.0 + sensor.gain_drift * std::sin(2.0 * kPi * t / sensor.gain_period_s + 0.7));
  canvas.convertTo(canvas, CV_32F, gain, 128.0 * (1.0 - sensor.contrast) + sensor.brightness_offset);
  if (sensor.blur_sigma_px > 0.0) cv::GaussianBlur(canvas, canvas, cv::Size(), sensor.blur_sigma_px);
  if (sensor.noise_sigma > 0.0) {
    cv::RNG rng(seed_ * 1000003ULL + static_cast<uint64_t>(index_) + 17ULL);
    cv::Mat noise(size, CV_32F);
    rng.fill(noise, cv::RNG::NORMAL, 0.0, sensor.noise_sigma);
    canvas += noise;
  }
  cv::Mat image8;
  canvas.convertTo(image8, CV_8U);
  frame.encoded_jpeg.clear();
  cv::imencode(".jpg", image8, frame.encoded_jpeg, {cv::IMWRITE_JPEG_QUALITY, sensor.jpeg_quality});
  frame.image = cv::imdecode(frame.encoded_jpeg, cv::IMREAD_GRAYSCALE);

  // Ground truth.
  frame.index = index_ + 1;
  frame.ground_to_image = image_from_raster;
  frame.homography_from_previous =
      index_ == 0 ? Homography::eye() : normalized(image_from_world * previous_image_from_world_.inv());
  frame.objects.clear();
  for (size_t k = 0; k < drawn.size(); ++k) {
    const detail::Vehicle& v = *drawn[k];
    ObjectTruth truth;
    truth.id = ids[k];
    truth.parked = v.parked;
    truth.speed_mps = v.parked ? 0.0 : v.speed_mps;
    truth.moving = !v.parked && v.speed_mps >= scenario_.traffic.moving_threshold_mps;
    truth.box = boxes[v.internal_id].first;
    truth.visibility = boxes[v.internal_id].second;
    // Hidden by structures: scale the in-image fraction by the share of its pixels still seen.
    if (const auto it = pixels.find(truth.id); it != pixels.end() && it->second.first > 0)
      truth.visibility *= static_cast<double>(it->second.second) / static_cast<double>(it->second.first);
    truth.kind = v.kind;
    const cv::Point2d now = apply_homography(image_from_world, v.position_m);
    const cv::Point2d before = apply_homography(image_from_world, v.position_m - v.velocity_mps * dt);
    truth.velocity_px = v.parked ? cv::Vec2d(0, 0) : cv::Vec2d(now.x - before.x, now.y - before.y);
    frame.objects.push_back(truth);
    if (truth.moving) moving_ids_.insert(truth.id);
    if (truth.parked) parked_ids_.insert(truth.id);
  }
  std::sort(frame.objects.begin(), frame.objects.end(), [](const ObjectTruth& a, const ObjectTruth& b) { return a.id < b.id; });

  previous_image_from_world_ = image_from_world;
  traffic_.step(dt);
  ++index_;
  return true;
}

Simulator::Simulator(Scenario scenario, uint64_t seed) : impl_(std::make_unique<Impl>(std::move(scenario), seed)) {}
Simulator::~Simulator() = default;
Simulator::Simulator(Simulator&&) noexcept = default;
Simulator& Simulator::operator=(Simulator&&) noexcept = default;

bool Simulator::next(SimFrame& frame) { return impl_->next(frame); }
int Simulator::frame_count() const { return impl_->scenario_.frames; }
const Scenario& Simulator::scenario() const { return impl_->scenario_; }
uint64_t Simulator::seed() const { return impl_->seed_; }
int Simulator::vehicles_seen() const { return static_cast<int>(impl_->public_ids_.size()); }
int Simulator::moving_vehicles_seen() const { return static_cast<int>(impl_->moving_ids_.size()); }
int Simulator::parked_vehicles_seen() const { return static_cast<int>(impl_->parked_ids_.size()); }

SceneInfo Simulator::scene() const {
  SceneInfo scene;
  scene.gsd_m = impl_->scenario_.camera.gsd_m;
  scene.fps = impl_->scenario_.fps;
  scene.vehicle_length_m = 4.5;
  scene.vehicle_width_m = 1.8;
  return scene;
}

const char* structure_kind_name(StructureKind kind) {
  switch (kind) {
    case StructureKind::Building: return "building";
    case StructureKind::Tree: return "tree";
    case StructureKind::Wall: return "wall";
  }
  return "?";
}

int object_at(const SimFrame& frame, cv::Point2d point, double tolerance_px) {
  const cv::Mat& mask = frame.object_id_mask;
  if (mask.empty()) return 0;
  const int x = static_cast<int>(std::lround(point.x)), y = static_cast<int>(std::lround(point.y));
  if (x >= 0 && y >= 0 && x < mask.cols && y < mask.rows && mask.at<int32_t>(y, x) != 0) return mask.at<int32_t>(y, x);
  if (tolerance_px <= 0.0) return 0;
  const int r = static_cast<int>(std::ceil(tolerance_px));
  int best = 0;
  double best_d2 = tolerance_px * tolerance_px + 1e-9;
  for (int yy = y - r; yy <= y + r; ++yy) {
    if (yy < 0 || yy >= mask.rows) continue;
    for (int xx = x - r; xx <= x + r; ++xx) {
      if (xx < 0 || xx >= mask.cols) continue;
      const int id = mask.at<int32_t>(yy, xx);
      if (id == 0) continue;
      const double d2 = (xx - point.x) * (xx - point.x) + (yy - point.y) * (yy - point.y);
      if (d2 < best_d2) {
        best_d2 = d2;
        best = id;
      }
    }
  }
  return best;
}

const ObjectTruth* find_object(const SimFrame& frame, int id) {
  for (const ObjectTruth& o : frame.objects)
    if (o.id == id) return &o;
  return nullptr;
}

bool is_on_moving_object(const SimFrame& frame, cv::Point2d point, double tolerance_px) {
  const ObjectTruth* o = find_object(frame, object_at(frame, point, tolerance_px));
  return o != nullptr && o->moving;
}

}  // namespace uavmot::sim
