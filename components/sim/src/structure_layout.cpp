#include "structure_layout.hpp"

#include <algorithm>
#include <cmath>
#include <random>

#include <opencv2/imgproc.hpp>

namespace uavmot::sim::detail {
namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr double kCell = 0.5;  // m, resolution of the occupancy grids

cv::Point2d unit(double angle) { return {std::cos(angle), std::sin(angle)}; }

// Occupancy of the ground on a 0.5 m grid: what is already taken.
class Occupancy {
 public:
  explicit Occupancy(cv::Rect2d region)
      : region_(region),
        grid_(cv::Mat::zeros(std::max(1, static_cast<int>(std::ceil(region.height / kCell))),
                             std::max(1, static_cast<int>(std::ceil(region.width / kCell))), CV_8U)) {}

  void mark_polygon(const std::vector<cv::Point2d>& world) {
    const std::vector<cv::Point> px = to_px(world);
    cv::fillConvexPoly(grid_, px, cv::Scalar(255), cv::LINE_8, 4);
  }
  void mark_polyline(const std::vector<cv::Point2d>& world, double width_m) {
    cv::polylines(grid_, to_px(world), false, cv::Scalar(255), std::max(1, static_cast<int>(std::lround(width_m / kCell))), cv::LINE_8, 4);
  }
  void mark_disc(cv::Point2d c, double radius_m) {
    const std::vector<cv::Point> px = to_px({c});
    cv::circle(grid_, px[0], std::max(16, static_cast<int>(std::lround(radius_m / kCell * 16.0))), cv::Scalar(255), cv::FILLED, cv::LINE_8, 4);
  }
  // True when no taken cell lies in the polygon (inside the region).
  bool free_polygon(const std::vector<cv::Point2d>& world) const {
    const std::vector<cv::Point> px = to_px(world);
    return !taken_in(cv::boundingRect(px), [&](cv::Mat& stamp, cv::Point shift) {
      std::vector<cv::Point> local;
      for (const cv::Point& p : px) local.push_back(p - shift);
      cv::fillConvexPoly(stamp, local, cv::Scalar(255), cv::LINE_8, 4);
    });
  }
  bool free_disc(cv::Point2d c, double radius_m) const {
    const cv::Point centre = to_px({c})[0];
    const int r16 = std::max(16, static_cast<int>(std::lround(radius_m / kCell * 16.0)));
    const cv::Rect bounds(centre.x - r16, centre.y - r16, 2 * r16 + 1, 2 * r16 + 1);
    return !taken_in(bounds, [&](cv::Mat& stamp, cv::Point shift) {
      cv::circle(stamp, centre - shift, r16, cv::Scalar(255), cv::FILLED, cv::LINE_8, 4);
    });
  }

 private:
  std::vector<cv::Point> to_px(const std::vector<cv::Point2d>& world) const {
    std::vector<cv::Point> px;
    for (const cv::Point2d& w : world)
      px.emplace_back(static_cast<int>(std::lround((w.x - region_.x) / kCell * 16.0)), static_cast<int>(std::lround((w.y - region_.y) / kCell * 16.0)));
    return px;
  }
  // Draws a shape (in 1/16-cell units, `bounds16` its bounding box) into a patch of the grid's
  // size around it and tells whether it covers a taken cell; only the patch is allocated.
  template <typename Draw>
  bool taken_in(cv::Rect bounds16, Draw draw) const {
    const cv::Rect cells(bounds16.x / 16 - 2, bounds16.y / 16 - 2, bounds16.width / 16 + 5, bounds16.height / 16 + 5);
    const cv::Rect roi = cells & cv::Rect(0, 0, grid_.cols, grid_.rows);
    if (roi.empty()) return false;
    cv::Mat stamp = cv::Mat::zeros(roi.size(), CV_8U);
    draw(stamp, cv::Point(roi.x * 16, roi.y * 16));
    cv::Mat both;
    cv::bitwise_and(stamp, grid_(roi), both);
    return cv::countNonZero(both) > 0;
  }

  cv::Rect2d region_;
  cv::Mat grid_;
};

std::vector<cv::Point2d> rectangle(cv::Point2d centre, double angle, double length, double width) {
  const cv::Point2d a = unit(angle) * (length / 2.0), c = unit(angle + kPi / 2.0) * (width / 2.0);
  return {centre + a + c, centre - a + c, centre - a - c, centre + a - c};
}

bool inside(cv::Rect2d region, cv::Point2d p) {
  return p.x >= region.x && p.y >= region.y && p.x <= region.x + region.width && p.y <= region.y + region.height;
}

// A random point on a road's centreline inside the region, with the road's tangent there.
bool roadside_point(const RoadNetwork& net, cv::Rect2d region, std::mt19937_64& rng, cv::Point2d& point, cv::Point2d& tangent,
                    double& half_width) {
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  const Road& road = net.roads[static_cast<size_t>(uni(rng) * static_cast<double>(net.roads.size())) % net.roads.size()];
  for (int tries = 0; tries < 20; ++tries) {
    const double s = uni(rng) * road.length();
    point = road.point_at(s);
    if (!inside(region, point)) continue;
    tangent = road.tangent_at(s);
    half_width = road.half_width();
    return true;
  }
  return false;
}

class Placer {
 public:
  Placer(const Scenario& scenario, const RoadNetwork& network, cv::Rect2d region, uint64_t seed)
      : p_(scenario.structures), net_(network), region_(region), rng_(seed ^ 0x57C0C7E5ULL), asphalt_(region), taken_(region) {
    for (const Road& road : net_.roads) asphalt_.mark_polyline(road.points, 2.0 * road.half_width());
    for (const auto& lot : net_.lots)
      asphalt_.mark_polygon(rectangle(lot.centre_m, lot.angle_rad, lot.along_m, lot.across_m + 4.0));
  }

  std::vector<Structure> run() {
    const double hectares = region_.width * region_.height / 1e4;
    place(StructureKind::Building, static_cast<int>(std::lround(p_.building_density_per_ha * hectares)));
    place(StructureKind::Wall, static_cast<int>(std::lround(p_.wall_density_per_ha * hectares)));
    place(StructureKind::Tree, static_cast<int>(std::lround(p_.tree_density_per_ha * hectares)));
    return std::move(placed_);
  }

 private:
  double uniform(double lo, double hi) { return lo + (hi - lo) * std::uniform_real_distribution<double>(0.0, 1.0)(rng_); }

  void place(StructureKind kind, int count) {
    int placed = 0;
    for (int attempt = 0; attempt < 40 * count && placed < count; ++attempt) {
      Structure s;
      s.kind = kind;
      s.look_seed = rng_();
      const bool ok = kind == StructureKind::Building ? try_building(s) : kind == StructureKind::Wall ? try_wall(s) : try_tree(s);
      if (!ok) continue;
      s.id = static_cast<int>(placed_.size()) + 1;
      placed_.push_back(s);
      ++placed;
    }
  }

  bool try_building(Structure& s) {
    s.length_m = uniform(p_.building_size_min_m, p_.building_size_max_m);
    s.width_m = uniform(p_.building_size_min_m, p_.building_size_max_m);
    // Taller buildings are rarer: a square-law draw leans toward the low end of the range.
    const double u = uniform(0.0, 1.0);
    s.height_m = p_.building_height_min_m + (p_.building_height_max_m - p_.building_height_min_m) * u * u;
    if (uniform(0.0, 1.0) < p_.building_roadside_fraction) {
      // Beside a road or the parking lot, facing it, 1.5-6 m from the asphalt.
      const double setback = uniform(1.5, 6.0), side = uniform(0.0, 1.0) < 0.5 ? -1.0 : 1.0;
      if (!net_.lots.empty() && uniform(0.0, 1.0) < 0.3) {
        const auto& lot = net_.lots[0];
        const cv::Point2d along = unit(lot.angle_rad), across = unit(lot.angle_rad + kPi / 2.0);
        s.angle_rad = lot.angle_rad;
        s.centre_m = lot.centre_m + along * uniform(-lot.along_m / 2.0, lot.along_m / 2.0) +
                     across * side * (lot.across_m / 2.0 + 2.0 + setback + s.width_m / 2.0);
      } else {
        cv::Point2d point, tangent;
        double half_width = 0.0;
        if (!roadside_point(net_, region_, rng_, point, tangent, half_width)) return false;
        s.angle_rad = std::atan2(tangent.y, tangent.x);
        s.centre_m = point + cv::Point2d(-tangent.y, tangent.x) * side * (half_width + setback + s.width_m / 2.0);
      }
    } else {
      s.centre_m = {uniform(region_.x, region_.x + region_.width), uniform(region_.y, region_.y + region_.height)};
      s.angle_rad = uniform(0.0, kPi);
    }
    const std::array<cv::Point2d, 4> corners = s.footprint();
    const std::vector<cv::Point2d> footprint(corners.begin(), corners.end());
    // 1.5 m of ground between a wall and the asphalt, 3 m between structures.
    if (!asphalt_.free_polygon(rectangle(s.centre_m, s.angle_rad, s.length_m + 3.0, s.width_m + 3.0))) return false;
    if (!taken_.free_polygon(rectangle(s.centre_m, s.angle_rad, s.length_m + 6.0, s.width_m + 6.0))) return false;
    taken_.mark_polygon(footprint);
    return true;
  }

  bool try_wall(Structure& s) {
    s.length_m = uniform(p_.wall_length_min_m, p_.wall_length_max_m);
    s.width_m = uniform(0.3, 0.5);
    s.height_m = uniform(p_.wall_height_min_m, p_.wall_height_max_m);
    // Walls line the roads (noise barriers, garden walls), 1-3 m off the asphalt.
    cv::Point2d point, tangent;
    double half_width = 0.0;
    if (!roadside_point(net_, region_, rng_, point, tangent, half_width)) return false;
    const double side = uniform(0.0, 1.0) < 0.5 ? -1.0 : 1.0;
    s.angle_rad = std::atan2(tangent.y, tangent.x);
    s.centre_m = point + cv::Point2d(-tangent.y, tangent.x) * side * (half_width + uniform(1.0, 3.0));
    if (!asphalt_.free_polygon(rectangle(s.centre_m, s.angle_rad, s.length_m + 1.0, s.width_m + 1.0))) return false;
    if (!taken_.free_polygon(rectangle(s.centre_m, s.angle_rad, s.length_m + 2.0, s.width_m + 2.0))) return false;
    const std::array<cv::Point2d, 4> corners = s.footprint();
    taken_.mark_polygon(std::vector<cv::Point2d>(corners.begin(), corners.end()));
    return true;
  }

  bool try_tree(Structure& s) {
    s.canopy_radius_m = uniform(p_.tree_radius_min_m, p_.tree_radius_max_m);
    // Bigger canopies on taller trees, within the configured height range.
    const double size = (s.canopy_radius_m - p_.tree_radius_min_m) / std::max(1e-9, p_.tree_radius_max_m - p_.tree_radius_min_m);
    const double mix = std::clamp(0.6 * size + 0.4 * uniform(0.0, 1.0), 0.0, 1.0);
    s.height_m = p_.tree_height_min_m + (p_.tree_height_max_m - p_.tree_height_min_m) * mix;
    s.canopy_base_m = std::max(1.5, s.height_m - std::max(2.0, 1.6 * s.canopy_radius_m));
    if (uniform(0.0, 1.0) < p_.tree_roadside_fraction) {
      // Trunk 0.8-2 m beside the asphalt: the canopy reaches over the outer lane.
      cv::Point2d point, tangent;
      double half_width = 0.0;
      if (!roadside_point(net_, region_, rng_, point, tangent, half_width)) return false;
      const double side = uniform(0.0, 1.0) < 0.5 ? -1.0 : 1.0;
      s.centre_m = point + cv::Point2d(-tangent.y, tangent.x) * side * (half_width + uniform(0.8, 2.0));
    } else {
      s.centre_m = {uniform(region_.x, region_.x + region_.width), uniform(region_.y, region_.y + region_.height)};
    }
    if (!asphalt_.free_disc(s.centre_m, 0.6)) return false;
    if (!taken_.free_disc(s.centre_m, 0.8 * s.canopy_radius_m)) return false;
    taken_.mark_disc(s.centre_m, 0.8 * s.canopy_radius_m);
    return true;
  }

  const StructureParams& p_;
  const RoadNetwork& net_;
  cv::Rect2d region_;
  std::mt19937_64 rng_;
  Occupancy asphalt_;  // roads and parking lots as painted
  Occupancy taken_;    // structures placed so far
  std::vector<Structure> placed_;
};

}  // namespace

std::array<cv::Point2d, 4> Structure::footprint() const {
  const std::vector<cv::Point2d> r = rectangle(centre_m, angle_rad, length_m, width_m);
  return {r[0], r[1], r[2], r[3]};
}

std::vector<Structure> place_structures(const Scenario& scenario, const RoadNetwork& network, cv::Rect2d region_m, uint64_t seed) {
  const StructureParams& p = scenario.structures;
  if (p.building_density_per_ha <= 0.0 && p.tree_density_per_ha <= 0.0 && p.wall_density_per_ha <= 0.0) return {};
  return Placer(scenario, network, region_m, seed).run();
}

}  // namespace uavmot::sim::detail
