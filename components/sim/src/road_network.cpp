#include "road_network.hpp"

#include <algorithm>
#include <cmath>
#include <random>

namespace uavmot::sim::detail {
namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr double kStep = 0.5;

cv::Point2d unit(double angle) { return {std::cos(angle), std::sin(angle)}; }

void finish_road(Road& road) {
  // Resample evenly, then arc lengths and curvature.
  std::vector<cv::Point2d> pts;
  pts.push_back(road.points.front());
  double carry = 0.0;
  for (size_t i = 1; i < road.points.size(); ++i) {
    const cv::Point2d a = road.points[i - 1], b = road.points[i];
    const double len = cv::norm(b - a);
    double s = kStep - carry;
    while (s <= len) {
      pts.push_back(a + (b - a) * (s / len));
      s += kStep;
    }
    carry = len - (s - kStep);
  }
  road.points = pts;
  road.arc.resize(pts.size());
  road.arc[0] = 0.0;
  for (size_t i = 1; i < pts.size(); ++i) road.arc[i] = road.arc[i - 1] + cv::norm(pts[i] - pts[i - 1]);
  road.curvature.assign(pts.size(), 0.0);
  for (size_t i = 1; i + 1 < pts.size(); ++i) {
    const cv::Point2d d1 = pts[i] - pts[i - 1], d2 = pts[i + 1] - pts[i];
    const double turn = std::atan2(d1.x * d2.y - d1.y * d2.x, d1.dot(d2));
    road.curvature[i] = std::abs(turn) / kStep;
  }
}

Road straight_road(cv::Point2d through, double angle, double half_length, int lanes, double lane_width) {
  Road road;
  road.lanes_per_direction = lanes;
  road.lane_width_m = lane_width;
  road.points = {through - unit(angle) * half_length, through + unit(angle) * half_length};
  finish_road(road);
  return road;
}

// Straight in, a 90-degree arc of `radius` around the corner, straight out.
Road bent_road(cv::Point2d corner, double angle_in, int turn_sign, double radius, double leg, int lanes, double lane_width) {
  Road road;
  road.lanes_per_direction = lanes;
  road.lane_width_m = lane_width;
  const cv::Point2d dir_in = unit(angle_in);
  const double angle_out = angle_in + turn_sign * kPi / 2.0;
  const cv::Point2d dir_out = unit(angle_out);
  const cv::Point2d arc_start = corner - dir_in * radius;
  const cv::Point2d arc_end = corner + dir_out * radius;
  road.points.push_back(arc_start - dir_in * leg);
  road.points.push_back(arc_start);
  const cv::Point2d centre = arc_start + dir_out * radius;
  const int steps = std::max(8, static_cast<int>(radius * kPi / 2.0 / kStep));
  for (int i = 1; i < steps; ++i) {
    const double a = angle_in + turn_sign * (kPi / 2.0) * i / steps;
    // Point on the arc: from the centre, pointing back opposite to the outward normal.
    road.points.push_back(centre - unit(a + turn_sign * kPi / 2.0) * radius);
  }
  road.points.push_back(arc_end);
  road.points.push_back(arc_end + dir_out * leg);
  finish_road(road);
  return road;
}

bool segment_intersection(cv::Point2d p, cv::Point2d p2, cv::Point2d q, cv::Point2d q2, double& t, double& u) {
  const cv::Point2d r = p2 - p, s = q2 - q;
  const double denom = r.x * s.y - r.y * s.x;
  if (std::abs(denom) < 1e-12) return false;
  const cv::Point2d qp = q - p;
  t = (qp.x * s.y - qp.y * s.x) / denom;
  u = (qp.x * r.y - qp.y * r.x) / denom;
  return t >= 0.0 && t <= 1.0 && u >= 0.0 && u <= 1.0;
}

void find_crossings(RoadNetwork& net) {
  for (size_t a = 0; a < net.roads.size(); ++a) {
    for (size_t b = a + 1; b < net.roads.size(); ++b) {
      const Road& ra = net.roads[a];
      const Road& rb = net.roads[b];
      // Coarse stride then exact segment test; roads are smooth so a 4 m stride is safe.
      const size_t stride = 8;
      for (size_t i = 0; i + stride < ra.points.size() + stride; i += stride) {
        const size_t i2 = std::min(i + stride, ra.points.size() - 1);
        if (i2 <= i) break;
        for (size_t j = 0; j + stride < rb.points.size() + stride; j += stride) {
          const size_t j2 = std::min(j + stride, rb.points.size() - 1);
          if (j2 <= j) break;
          double t = 0, u = 0;
          if (segment_intersection(ra.points[i], ra.points[i2], rb.points[j], rb.points[j2], t, u)) {
            net.crossings.push_back({static_cast<int>(a), static_cast<int>(b),
                                     ra.arc[i] + t * (ra.arc[i2] - ra.arc[i]),
                                     rb.arc[j] + u * (rb.arc[j2] - rb.arc[j])});
          }
        }
      }
    }
  }
}

}  // namespace

cv::Point2d Road::point_at(double s) const {
  s = std::clamp(s, 0.0, length());
  const size_t i = std::min(points.size() - 2, static_cast<size_t>(s / kStep));
  const double seg = arc[i + 1] - arc[i];
  const double f = seg > 0 ? (s - arc[i]) / seg : 0.0;
  return points[i] + (points[i + 1] - points[i]) * f;
}

cv::Point2d Road::tangent_at(double s) const {
  s = std::clamp(s, 0.0, length());
  const size_t i = std::min(points.size() - 2, static_cast<size_t>(s / kStep));
  // Blend neighbouring segment directions so the heading turns smoothly on arcs.
  const auto dir = [&](size_t k) {
    const cv::Point2d d = points[k + 1] - points[k];
    return d * (1.0 / std::max(1e-9, cv::norm(d)));
  };
  const double f = std::clamp((s - arc[i]) / kStep, 0.0, 1.0);
  cv::Point2d d = dir(i);
  if (i + 2 < points.size()) d = d * (1.0 - f) + dir(i + 1) * f;
  return d * (1.0 / std::max(1e-9, cv::norm(d)));
}

double Road::curvature_at(double s) const {
  s = std::clamp(s, 0.0, length());
  return curvature[std::min(curvature.size() - 1, static_cast<size_t>(s / kStep))];
}

double Road::max_curvature_ahead(double s, double ahead) const {
  double k = 0.0;
  for (double x = std::max(0.0, s); x <= std::min(length(), s + ahead); x += 2.0 * kStep) k = std::max(k, curvature_at(x));
  return k;
}

double distance_to_road(const Road& road, cv::Point2d p) {
  double best = 1e300;
  for (size_t i = 0; i + 1 < road.points.size(); ++i) {
    const cv::Point2d a = road.points[i], d = road.points[i + 1] - a;
    const double len2 = d.dot(d);
    const double t = len2 > 0 ? std::clamp((p - a).dot(d) / len2, 0.0, 1.0) : 0.0;
    best = std::min(best, cv::norm(p - (a + d * t)));
  }
  return best;
}

RoadNetwork make_road_network(const Scenario& scenario, cv::Point2d centre, double extent, double view_radius,
                              uint64_t seed) {
  std::mt19937_64 rng(seed ^ 0x80AD5ULL);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  const RoadParams& p = scenario.roads;
  RoadNetwork net;

  const double main_angle = (scenario.camera.heading_deg + p.main_road_angle_deg) * kPi / 180.0;
  const double half = extent + 60.0;
  // The main road runs through the middle of the view, a little off-centre.
  const cv::Point2d main_through = centre + unit(main_angle + kPi / 2.0) * ((uni(rng) - 0.5) * 0.2 * view_radius);
  Road main = straight_road(main_through, main_angle, half, p.main_lanes_per_direction, p.lane_width_m);
  main.main = true;
  net.roads.push_back(main);

  for (int i = 0; i < p.cross_roads; ++i) {
    const double along = (uni(rng) - 0.5) * 1.2 * view_radius;
    const cv::Point2d through = main_through + unit(main_angle) * along;
    const double angle = main_angle + (60.0 + 60.0 * uni(rng)) * kPi / 180.0;
    Road road = straight_road(through, angle, half, p.side_lanes_per_direction, p.lane_width_m);
    road.parking_strip = (i % 2 == 0);
    net.roads.push_back(road);
  }
  for (int i = 0; i < p.curved_roads; ++i) {
    // Corner well inside the view on one side of the main road so the bend is seen.
    const double side = (i % 2 == 0) ? 1.0 : -1.0;
    const cv::Point2d corner = main_through + unit(main_angle) * ((uni(rng) - 0.5) * 0.8 * view_radius) +
                               unit(main_angle + kPi / 2.0) * side * (0.25 + 0.2 * uni(rng)) * view_radius;
    const double angle_in = main_angle + (uni(rng) < 0.5 ? 0.0 : kPi);
    const int turn = uni(rng) < 0.5 ? 1 : -1;
    const double radius = 15.0 + 20.0 * uni(rng);
    Road road = bent_road(corner, angle_in, turn, radius, half, p.side_lanes_per_direction, p.lane_width_m);
    net.roads.push_back(road);
  }
  find_crossings(net);

  // A parking lot beside the main road, with stalls perpendicular to it.
  if (scenario.traffic.parked_vehicles > 0) {
    // Try places along both sides of the main road until one is clear of the other roads.
    for (int attempt = 0; attempt < 40; ++attempt) {
      RoadNetwork::Lot lot;
      const double side = uni(rng) < 0.5 ? 1.0 : -1.0;
      lot.along_m = 40.0;
      lot.across_m = 16.0;
      lot.angle_rad = main_angle;
      lot.centre_m = main_through + unit(main_angle) * ((uni(rng) - 0.5) * 1.2 * view_radius) +
                     unit(main_angle + kPi / 2.0) * side * (main.half_width() + 2.0 + lot.across_m / 2.0);
      if (cv::norm(lot.centre_m - centre) > 0.7 * view_radius) continue;
      bool clear = true;
      for (size_t r = 1; r < net.roads.size(); ++r)
        if (distance_to_road(net.roads[r], lot.centre_m) < net.roads[r].half_width() + 28.0) clear = false;
      if (!clear) continue;
      net.lots.push_back(lot);
      const cv::Point2d along = unit(lot.angle_rad), across = unit(lot.angle_rad + kPi / 2.0);
      for (int row = 0; row < 2; ++row) {
        for (int k = 0; k < 14; ++k) {
          ParkingSpot spot;
          spot.centre_m = lot.centre_m + along * ((k - 6.5) * 2.7) + across * ((row - 0.5) * 10.0);
          spot.heading_rad = lot.angle_rad + kPi / 2.0 + (uni(rng) < 0.5 ? 0.0 : kPi);
          net.parking_spots.push_back(spot);
        }
      }
      break;
    }
    // Parallel parking on the strips of side roads, within the view.
    for (size_t r = 1; r < net.roads.size(); ++r) {
      const Road& road = net.roads[r];
      if (!road.parking_strip) continue;
      for (double s = 0.0; s < road.length(); s += 6.5) {
        const cv::Point2d c = road.point_at(s);
        if (cv::norm(c - centre) > view_radius * 1.2) continue;
        bool near_crossing = false;
        for (const Crossing& x : net.crossings)
          if ((x.road_a == static_cast<int>(r) && std::abs(x.s_a - s) < 20.0) ||
              (x.road_b == static_cast<int>(r) && std::abs(x.s_b - s) < 20.0))
            near_crossing = true;
        if (near_crossing) continue;
        const cv::Point2d t = road.tangent_at(s);
        const cv::Point2d n(-t.y, t.x);
        const double offset = road.lanes_per_direction * road.lane_width_m + 1.2;
        for (double sign : {1.0, -1.0}) {
          ParkingSpot spot;
          spot.centre_m = c + n * (sign * offset);
          spot.heading_rad = std::atan2(t.y, t.x) + (sign > 0 ? 0.0 : kPi);
          // Stay clear of every other road.
          bool ok = true;
          for (size_t o = 0; o < net.roads.size(); ++o)
            if (o != r && distance_to_road(net.roads[o], spot.centre_m) < net.roads[o].half_width() + 4.0) ok = false;
          if (ok) net.parking_spots.push_back(spot);
        }
      }
    }
  }
  return net;
}

}  // namespace uavmot::sim::detail
