#pragma once
// Latitude/longitude <-> local east/north metres around an origin, the flat-earth approximation
// the frame footprint uses: east = dlon * N(lat0) * cos(lat0), north = dlat * M(lat0), with the
// WGS84 meridional (M) and prime-vertical (N) radii of curvature at the origin. Within 1 km of the
// origin the distances it gives differ from the WGS84 geodesic by well under 1 cm (the error grows
// as (d / R)^2 and with the change of cos(lat) across the area); heights are ignored (the ground
// is the ellipsoid's tangent plane through the origin).

#include <opencv2/core/types.hpp>

namespace uavmot::geo {

struct LatLon {
  double lat_deg = 0.0;
  double lon_deg = 0.0;
};

class LocalTangentPlane {
 public:
  explicit LocalTangentPlane(LatLon origin);

  LatLon origin() const { return origin_; }
  cv::Point2d to_east_north(LatLon p) const;  // metres
  LatLon to_lat_lon(cv::Point2d east_north) const;

 private:
  LatLon origin_;
  double metres_per_deg_lat_;
  double metres_per_deg_lon_;
};

// Ground distance in metres between two nearby points (the plane above, centred between them).
double ground_distance_m(LatLon a, LatLon b);

}  // namespace uavmot::geo
