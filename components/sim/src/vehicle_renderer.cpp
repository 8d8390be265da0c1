#include "vehicle_renderer.hpp"

#include <algorithm>
#include <cmath>

#include <opencv2/core.hpp>

#include "uavmot/core/homography.hpp"

namespace uavmot::sim::detail {
namespace {
constexpr int kSub = 4;  // supersampling per axis
constexpr double kPi = 3.14159265358979323846;

bool inside_rounded_rect(double u, double v, double half_l, double half_w, double radius) {
  const double au = std::abs(u), av = std::abs(v);
  if (au > half_l || av > half_w) return false;
  const double du = au - (half_l - radius), dv = av - (half_w - radius);
  if (du > 0.0 && dv > 0.0) return du * du + dv * dv <= radius * radius;
  return true;
}

// Gray level of the vehicle's top at local (u along, v across), u = +L/2 at the front.
double vehicle_gray(const Vehicle& veh, double u, double v) {
  const double l = veh.length_m, w = veh.width_m;
  const double f = (l / 2.0 - u) / l;  // 0 at the front bumper, 1 at the rear
  const double edge = std::min(w / 2.0 - std::abs(v), std::min(l / 2.0 - std::abs(u), 10.0));
  double gray = veh.look.body;
  const bool window_band = std::abs(v) < w / 2.0 - 0.14;
  switch (veh.kind) {
    case VehicleKind::Car:
      if (f > 0.24 && f < 0.37 && window_band) gray = veh.look.glass;
      else if (f >= 0.37 && f < 0.71 && window_band) gray = veh.look.roof;
      else if (f >= 0.71 && f < 0.81 && window_band) gray = veh.look.glass;
      break;
    case VehicleKind::Van:
      if (f > 0.10 && f < 0.21 && window_band) gray = veh.look.glass;
      else if (f >= 0.21 && window_band) gray = veh.look.roof;
      break;
    case VehicleKind::Truck: {
      const double cab = 2.3 / l;
      if (f > cab && f < cab + 0.35 / l) gray = 35.0;  // gap between cab and box
      else if (f >= cab + 0.35 / l) gray = veh.look.cargo;
      else if (f > 0.3 / l && f < 1.0 / l && window_band) gray = veh.look.glass;
      break;
    }
  }
  // A darker rim: the body's sides curve away from the sun-lit top.
  if (edge < 0.12) gray *= 0.82;
  return gray;
}

cv::Matx33d world_from_local(const Vehicle& v, cv::Point2d offset = {0, 0}) {
  const double c = std::cos(v.heading_rad), s = std::sin(v.heading_rad);
  return cv::Matx33d(c, -s, v.position_m.x + offset.x, s, c, v.position_m.y + offset.y, 0, 0, 1);
}

// Pixel bounds of the local rectangle [-hl, hl] x [-hw, hw] mapped by image_from_local.
cv::Rect pixel_bounds(const cv::Matx33d& image_from_local, double hl, double hw, cv::Size size) {
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  for (double su : {-1.0, 1.0})
    for (double sv : {-1.0, 1.0}) {
      const cv::Point2d p = apply_homography(image_from_local, {su * hl, sv * hw});
      x0 = std::min(x0, p.x);
      y0 = std::min(y0, p.y);
      x1 = std::max(x1, p.x);
      y1 = std::max(y1, p.y);
    }
  const cv::Rect r(static_cast<int>(std::floor(x0)) - 1, static_cast<int>(std::floor(y0)) - 1,
                   static_cast<int>(std::ceil(x1) - std::floor(x0)) + 3, static_cast<int>(std::ceil(y1) - std::floor(y0)) + 3);
  return r & cv::Rect(0, 0, size.width, size.height);
}

}  // namespace

OrientedBox image_box(const Vehicle& vehicle, const cv::Matx33d& image_from_world) {
  const cv::Matx33d m = image_from_world * world_from_local(vehicle);
  const cv::Point2d centre = apply_homography(m, {0, 0});
  const cv::Point2d along = apply_homography(m, {vehicle.length_m / 2, 0}) - apply_homography(m, {-vehicle.length_m / 2, 0});
  const cv::Point2d across = apply_homography(m, {0, vehicle.width_m / 2}) - apply_homography(m, {0, -vehicle.width_m / 2});
  OrientedBox box;
  box.cx = centre.x;
  box.cy = centre.y;
  box.length = cv::norm(along);
  box.width = cv::norm(across);
  box.angle_deg = normalize_axis_angle_deg(std::atan2(along.y, along.x) * 180.0 / kPi);
  return box;
}

void render_vehicles(cv::Mat& image, cv::Mat& id_mask, const std::vector<const Vehicle*>& vehicles, const std::vector<int>& ids,
                     const cv::Matx33d& image_from_world, const ShadowParams& shadow) {
  const cv::Size size = image.size();
  // Shadows first so no vehicle is darkened by its neighbour's shadow.
  if (shadow.strength > 0.0) {
    for (const Vehicle* v : vehicles) {
      const cv::Matx33d m = image_from_world * world_from_local(*v, shadow.offset_m);
      const double hl = v->length_m / 2.0 + 0.1, hw = v->width_m / 2.0 + 0.1;
      const cv::Rect bounds = pixel_bounds(m, hl, hw, size);
      if (bounds.empty()) continue;
      const cv::Matx33d local_from_image = m.inv();
      for (int y = bounds.y; y < bounds.y + bounds.height; ++y) {
        float* row = image.ptr<float>(y);
        for (int x = bounds.x; x < bounds.x + bounds.width; ++x) {
          int hits = 0;
          for (int j = 0; j < kSub; ++j)
            for (int i = 0; i < kSub; ++i) {
              const double px = x - 0.5 + (i + 0.5) / kSub, py = y - 0.5 + (j + 0.5) / kSub;
              const double w = local_from_image(2, 0) * px + local_from_image(2, 1) * py + local_from_image(2, 2);
              const double u = (local_from_image(0, 0) * px + local_from_image(0, 1) * py + local_from_image(0, 2)) / w;
              const double vv = (local_from_image(1, 0) * px + local_from_image(1, 1) * py + local_from_image(1, 2)) / w;
              if (inside_rounded_rect(u, vv, hl, hw, 0.5)) ++hits;
            }
          row[x] *= static_cast<float>(1.0 - shadow.strength * hits / (kSub * kSub));
        }
      }
    }
  }
  for (size_t k = 0; k < vehicles.size(); ++k) {
    const Vehicle& veh = *vehicles[k];
    const cv::Matx33d m = image_from_world * world_from_local(veh);
    const double hl = veh.length_m / 2.0, hw = veh.width_m / 2.0;
    const cv::Rect bounds = pixel_bounds(m, hl, hw, size);
    if (bounds.empty()) continue;
    const double radius = veh.kind == VehicleKind::Car ? 0.35 : 0.2;
    const cv::Matx33d local_from_image = m.inv();
    for (int y = bounds.y; y < bounds.y + bounds.height; ++y) {
      float* row = image.ptr<float>(y);
      int32_t* ids_row = id_mask.ptr<int32_t>(y);
      for (int x = bounds.x; x < bounds.x + bounds.width; ++x) {
        int hits = 0;
        double sum = 0.0;
        for (int j = 0; j < kSub; ++j)
          for (int i = 0; i < kSub; ++i) {
            const double px = x - 0.5 + (i + 0.5) / kSub, py = y - 0.5 + (j + 0.5) / kSub;
            const double w = local_from_image(2, 0) * px + local_from_image(2, 1) * py + local_from_image(2, 2);
            const double u = (local_from_image(0, 0) * px + local_from_image(0, 1) * py + local_from_image(0, 2)) / w;
            const double vv = (local_from_image(1, 0) * px + local_from_image(1, 1) * py + local_from_image(1, 2)) / w;
            if (inside_rounded_rect(u, vv, hl, hw, radius)) {
              ++hits;
              sum += vehicle_gray(veh, u, vv);
            }
          }
        if (hits == 0) continue;
        const double coverage = static_cast<double>(hits) / (kSub * kSub);
        row[x] = static_cast<float>(row[x] * (1.0 - coverage) + sum / (kSub * kSub));
        if (2 * hits >= kSub * kSub) ids_row[x] = ids[k];
      }
    }
  }
}

}  // namespace uavmot::sim::detail
