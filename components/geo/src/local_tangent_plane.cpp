#include "uavmot/geo/local_tangent_plane.hpp"

#include <cmath>
#include <numbers>

namespace uavmot::geo {

namespace {

constexpr double kWgs84SemiMajorM = 6378137.0;
constexpr double kWgs84Flattening = 1.0 / 298.257223563;
constexpr double kWgs84E2 = kWgs84Flattening * (2.0 - kWgs84Flattening);
constexpr double kRadPerDeg = std::numbers::pi / 180.0;

}  // namespace

LocalTangentPlane::LocalTangentPlane(LatLon origin) : origin_(origin) {
  const double s = std::sin(origin.lat_deg * kRadPerDeg);
  const double w = std::sqrt(1.0 - kWgs84E2 * s * s);
  const double prime_vertical = kWgs84SemiMajorM / w;
  const double meridional = kWgs84SemiMajorM * (1.0 - kWgs84E2) / (w * w * w);
  metres_per_deg_lat_ = meridional * kRadPerDeg;
  metres_per_deg_lon_ = prime_vertical * std::cos(origin.lat_deg * kRadPerDeg) * kRadPerDeg;
}

cv::Point2d LocalTangentPlane::to_east_north(LatLon p) const {
  double dlon = p.lon_deg - origin_.lon_deg;
  if (dlon > 180.0) dlon -= 360.0;  // across the antimeridian
  if (dlon < -180.0) dlon += 360.0;
  return {dlon * metres_per_deg_lon_, (p.lat_deg - origin_.lat_deg) * metres_per_deg_lat_};
}

LatLon LocalTangentPlane::to_lat_lon(cv::Point2d east_north) const {
  double lon = origin_.lon_deg + east_north.x / metres_per_deg_lon_;
  if (lon > 180.0) lon -= 360.0;
  if (lon < -180.0) lon += 360.0;
  return {origin_.lat_deg + east_north.y / metres_per_deg_lat_, lon};
}

double ground_distance_m(LatLon a, LatLon b) {
  const LocalTangentPlane plane({(a.lat_deg + b.lat_deg) / 2.0, a.lon_deg});
  const cv::Point2d d = plane.to_east_north(b) - plane.to_east_north(a);
  return std::hypot(d.x, d.y);
}

}  // namespace uavmot::geo
