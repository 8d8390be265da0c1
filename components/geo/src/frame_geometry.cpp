#include "uavmot/geo/frame_geometry.hpp"

#include <cmath>
#include <numbers>

#include <Eigen/Dense>

#include "uavmot/core/error.hpp"
#include "uavmot/core/homography.hpp"

namespace uavmot::geo {

namespace {

bool valid_lat_lon(double lat, double lon) {
  return std::isfinite(lat) && std::isfinite(lon) && std::abs(lat) <= 90.0 && std::abs(lon) <= 180.0;
}

// The homography taking src[i] to dst[i] (h33 = 1), from the 8x8 linear system; nullopt when the
// points are degenerate (three collinear, repeated) or the result is not finite.
std::optional<cv::Matx33d> four_point_homography(const std::array<cv::Point2d, 4>& src, const std::array<cv::Point2d, 4>& dst) {
  Eigen::Matrix<double, 8, 8> a;
  Eigen::Matrix<double, 8, 1> b;
  for (int i = 0; i < 4; ++i) {
    const double x = src[static_cast<std::size_t>(i)].x, y = src[static_cast<std::size_t>(i)].y;
    const double u = dst[static_cast<std::size_t>(i)].x, v = dst[static_cast<std::size_t>(i)].y;
    a.row(2 * i) << x, y, 1, 0, 0, 0, -u * x, -u * y;
    a.row(2 * i + 1) << 0, 0, 0, x, y, 1, -v * x, -v * y;
    b(2 * i) = u;
    b(2 * i + 1) = v;
  }
  const Eigen::FullPivLU<Eigen::Matrix<double, 8, 8>> lu(a);
  if (lu.rank() < 8) return std::nullopt;
  const Eigen::Matrix<double, 8, 1> h = lu.solve(b);
  cv::Matx33d m(h(0), h(1), h(2), h(3), h(4), h(5), h(6), h(7), 1.0);
  if (!is_finite(m)) return std::nullopt;
  return m;
}

// A mapping is usable when every image corner lands in front of the camera (w > 0), i.e. the
// footprint is a convex quadrilateral the image does not fold over.
bool maps_in_front(const cv::Matx33d& h, const std::array<cv::Point2d, 4>& points) {
  for (const cv::Point2d& p : points) {
    if (h(2, 0) * p.x + h(2, 1) * p.y + h(2, 2) <= 0.0) return false;
  }
  return true;
}

std::optional<cv::Point2d> apply_in_front(const cv::Matx33d& h, cv::Point2d p) {
  const double w = h(2, 0) * p.x + h(2, 1) * p.y + h(2, 2);
  if (!(w > 0.0)) return std::nullopt;
  return cv::Point2d((h(0, 0) * p.x + h(0, 1) * p.y + h(0, 2)) / w, (h(1, 0) * p.x + h(1, 1) * p.y + h(1, 2)) / w);
}

}  // namespace

const char* to_string(GsdSource source) {
  switch (source) {
    case GsdSource::kFootprint: return "footprint";
    case GsdSource::kSlantRangeFov: return "slant range and horizontal FOV";
    case GsdSource::kTargetWidth: return "target width";
    case GsdSource::kNone: break;
  }
  return "none";
}

std::array<cv::Point2d, 4> image_corners(cv::Size s) {
  const double right = s.width - 0.5, bottom = s.height - 0.5;
  return {cv::Point2d(-0.5, -0.5), cv::Point2d(right, -0.5), cv::Point2d(right, bottom), cv::Point2d(-0.5, bottom)};
}

cv::Point2d image_center(cv::Size s) { return {(s.width - 1) / 2.0, (s.height - 1) / 2.0}; }

std::optional<std::array<LatLon, 4>> ground_corners(const UasMetadata& m) {
  std::array<LatLon, 4> corners;
  bool full = true;
  for (std::size_t i = 0; i < 4; ++i) full = full && m.corner_latitude_deg[i] && m.corner_longitude_deg[i];
  if (full) {
    for (std::size_t i = 0; i < 4; ++i) corners[i] = {*m.corner_latitude_deg[i], *m.corner_longitude_deg[i]};
  } else {
    if (!m.frame_center_latitude_deg || !m.frame_center_longitude_deg) return std::nullopt;
    for (std::size_t i = 0; i < 4; ++i) {
      if (!m.offset_corner_latitude_deg[i] || !m.offset_corner_longitude_deg[i]) return std::nullopt;
      corners[i] = {*m.frame_center_latitude_deg + *m.offset_corner_latitude_deg[i],
                    *m.frame_center_longitude_deg + *m.offset_corner_longitude_deg[i]};
    }
  }
  for (const LatLon& c : corners) {
    if (!valid_lat_lon(c.lat_deg, c.lon_deg)) return std::nullopt;
  }
  return corners;
}

FrameGeometry FrameGeometry::from_metadata(const UasMetadata& m, cv::Size image_size) {
  if (image_size.width <= 0 || image_size.height <= 0) {
    throw InvalidArgument("FrameGeometry: image size must be positive, got " + std::to_string(image_size.width) + "x" +
                          std::to_string(image_size.height));
  }
  const auto corners = ground_corners(m);
  std::optional<LatLon> center;
  if (m.frame_center_latitude_deg && m.frame_center_longitude_deg &&
      valid_lat_lon(*m.frame_center_latitude_deg, *m.frame_center_longitude_deg)) {
    center = LatLon{*m.frame_center_latitude_deg, *m.frame_center_longitude_deg};
  }
  LatLon origin = center.value_or(LatLon{});
  if (!center && corners) {
    for (const LatLon& c : *corners) origin = {origin.lat_deg + c.lat_deg / 4.0, origin.lon_deg + c.lon_deg / 4.0};
  }

  FrameGeometry g(image_size, origin);
  g.corners_ = corners;
  g.center_ = center;
  if (corners) {
    std::array<cv::Point2d, 4> ground;
    for (std::size_t i = 0; i < 4; ++i) ground[i] = g.plane_.to_east_north((*corners)[i]);
    const auto image = image_corners(image_size);
    const auto forward = four_point_homography(image, ground);
    const auto backward = four_point_homography(ground, image);
    if (forward && backward && maps_in_front(*forward, image) && maps_in_front(*backward, ground)) {
      g.image_to_ground_ = forward;
      g.ground_to_image_ = backward;
    }
  }

  const double width = image_size.width;
  if (g.image_to_ground_) {
    const cv::Matx22d j = homography_jacobian(*g.image_to_ground_, image_center(image_size));
    g.gsd_x_ = std::hypot(j(0, 0), j(1, 0));
    g.gsd_y_ = std::hypot(j(0, 1), j(1, 1));
    g.gsd_ = (*g.gsd_x_ + *g.gsd_y_) / 2.0;
    g.gsd_source_ = GsdSource::kFootprint;
  } else if (m.slant_range_m && m.sensor_hfov_deg && *m.slant_range_m > 0.0 && *m.sensor_hfov_deg > 0.0 &&
             *m.sensor_hfov_deg < 180.0) {
    g.gsd_ = 2.0 * *m.slant_range_m * std::tan(*m.sensor_hfov_deg * std::numbers::pi / 360.0) / width;
    g.gsd_source_ = GsdSource::kSlantRangeFov;
  } else if (m.target_width_m && *m.target_width_m > 0.0) {
    g.gsd_ = *m.target_width_m / width;
    g.gsd_source_ = GsdSource::kTargetWidth;
  }
  return g;
}

std::optional<LatLon> FrameGeometry::pixel_to_lat_lon(cv::Point2d pixel) const {
  if (!image_to_ground_) return std::nullopt;
  const auto en = apply_in_front(*image_to_ground_, pixel);
  if (!en) return std::nullopt;
  return plane_.to_lat_lon(*en);
}

std::optional<cv::Point2d> FrameGeometry::lat_lon_to_pixel(LatLon point) const {
  if (!ground_to_image_ || !valid_lat_lon(point.lat_deg, point.lon_deg)) return std::nullopt;
  return apply_in_front(*ground_to_image_, plane_.to_east_north(point));
}

}  // namespace uavmot::geo
