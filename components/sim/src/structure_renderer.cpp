#include "structure_renderer.hpp"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

#include "structure_looks.hpp"

namespace uavmot::sim::detail {
namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr int kCanopyVertices = 28;

cv::Point3d at_height(cv::Point2d ground, double height_m) { return {ground.x, ground.y, -height_m}; }

// Lobed crown outline (world, at one height): radius varies smoothly around the trunk.
std::vector<cv::Point3d> crown_ring(const Structure& s, double height_m, double scale) {
  cv::RNG rng(s.look_seed ^ 0xC20A7ULL);
  const double p1 = rng.uniform(0.0, 2.0 * kPi), p2 = rng.uniform(0.0, 2.0 * kPi);
  const int lobes = 3 + static_cast<int>(rng.uniform(0, 3));
  std::vector<cv::Point3d> ring;
  for (int k = 0; k < kCanopyVertices; ++k) {
    const double a = 2.0 * kPi * k / kCanopyVertices;
    const double r = s.canopy_radius_m * scale * (0.86 + 0.09 * std::sin(lobes * a + p1) + 0.05 * std::sin((2 * lobes + 1) * a + p2));
    ring.push_back(at_height(s.centre_m + cv::Point2d(std::cos(a), std::sin(a)) * r, height_m));
  }
  return ring;
}

cv::Point2d project(const cv::Matx34d& p, const cv::Point3d& x, double& depth) {
  const cv::Vec3d h = p * cv::Vec4d(x.x, x.y, x.z, 1.0);
  depth = h[2];
  return {h[0] / h[2], h[1] / h[2]};
}

}  // namespace

// A planar face: texture pixel (i, j) lies at origin + i * u + j * v (world metres).
struct StructureRenderer::Face {
  cv::Point3d origin;
  cv::Vec3d u, v;
  int texture = 0;
  std::vector<cv::Point3d> outline;  // drawn polygon (world)
  bool hull = false;                 // draw the image convex hull of the outline (a crown's flank)
  cv::Vec3d normal{0, 0, 0};         // outward normal of a wall; zero = always drawn
  double gain = 1.0;
};

struct StructureRenderer::Solid {
  int id = 0;
  StructureKind kind = StructureKind::Building;
  double height_m = 0.0;
  cv::Point3d middle;               // depth reference for the painter's algorithm
  std::vector<cv::Point3d> corners;  // every vertex: the silhouette is their image convex hull
  std::vector<Face> faces;           // in drawing order
};

StructureRenderer::StructureRenderer(const std::vector<Structure>& structures, const StructureParams& params) {
  const double az = params.sun_azimuth_deg * kPi / 180.0, el = params.sun_elevation_deg * kPi / 180.0;
  const cv::Vec3d sun(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), -std::sin(el));  // toward the sun
  const double t = kStructureTexelM;
  for (const Structure& s : structures) {
    Solid solid;
    solid.id = s.id;
    solid.kind = s.kind;
    solid.height_m = s.height_m;
    solid.middle = at_height(s.centre_m, s.height_m / 2.0);
    if (s.kind == StructureKind::Tree) {
      const double top = s.height_m - 0.2 * s.canopy_radius_m;
      const std::vector<cv::Point3d> upper = crown_ring(s, top, 1.0);
      const std::vector<cv::Point3d> lower = crown_ring(s, s.canopy_base_m + 0.3 * (top - s.canopy_base_m), 0.85);
      // Trunk: two crossed bark-coloured quads from the ground to the crown.
      cv::Mat bark(std::max(2, static_cast<int>(s.canopy_base_m / t) + 1), 4, CV_32F, cv::Scalar(48.0));
      textures_.push_back(bark);
      for (const cv::Vec3d& across : {cv::Vec3d(1, 0, 0), cv::Vec3d(0, 1, 0)}) {
        Face trunk;
        const cv::Point3d base = at_height(s.centre_m, s.canopy_base_m) - cv::Point3d(across[0], across[1], 0) * 0.25;
        trunk.origin = base;
        trunk.u = across * t;
        trunk.v = cv::Vec3d(0, 0, t);
        trunk.texture = static_cast<int>(textures_.size()) - 1;
        const cv::Point3d w(across[0] * 0.5, across[1] * 0.5, 0.0), down(0, 0, s.canopy_base_m);
        trunk.outline = {base, base + w, base + w + down, base + down};
        solid.faces.push_back(trunk);
      }
      textures_.push_back(canopy_texture(s, cv::Point2d(sun[0], sun[1])));
      Face crown;
      crown.origin = at_height(s.centre_m - cv::Point2d(s.canopy_radius_m, s.canopy_radius_m), top);
      crown.u = cv::Vec3d(t, 0, 0);
      crown.v = cv::Vec3d(0, t, 0);
      crown.texture = static_cast<int>(textures_.size()) - 1;
      Face flank = crown;  // the crown's side, seen in oblique views: the same leaves in shade
      flank.outline = upper;
      flank.outline.insert(flank.outline.end(), lower.begin(), lower.end());
      flank.hull = true;
      flank.gain = 0.7;
      crown.outline = upper;
      solid.faces.push_back(flank);
      solid.faces.push_back(crown);
      solid.corners = flank.outline;
      solid.corners.push_back(at_height(s.centre_m, 0.0));
    } else {
      const std::array<cv::Point2d, 4> foot = s.footprint();
      for (int k = 0; k < 4; ++k) {
        const cv::Point2d a = foot[k], b = foot[(k + 1) % 4];
        const cv::Point2d d = b - a;
        const double len = cv::norm(d);
        cv::Point2d n(d.y / len, -d.x / len);
        if (n.dot((a + b) * 0.5 - s.centre_m) < 0.0) n = -n;
        const double lambert = std::max(0.0, n.x * sun[0] + n.y * sun[1]);
        textures_.push_back(facade_texture(s, len, 0.5 + 0.6 * lambert, k));
        Face wall;
        wall.origin = at_height(a, s.height_m);
        wall.u = cv::Vec3d(d.x / len * t, d.y / len * t, 0);
        wall.v = cv::Vec3d(0, 0, t);
        wall.texture = static_cast<int>(textures_.size()) - 1;
        wall.outline = {at_height(a, s.height_m), at_height(b, s.height_m), at_height(b, 0.0), at_height(a, 0.0)};
        wall.normal = cv::Vec3d(n.x, n.y, 0);
        solid.faces.push_back(wall);
      }
      textures_.push_back(roof_texture(s));
      Face roof;
      const cv::Point2d along(std::cos(s.angle_rad), std::sin(s.angle_rad)), across(-along.y, along.x);
      roof.origin = at_height(s.centre_m - along * (s.length_m / 2.0) - across * (s.width_m / 2.0), s.height_m);
      roof.u = cv::Vec3d(along.x * t, along.y * t, 0);
      roof.v = cv::Vec3d(across.x * t, across.y * t, 0);
      roof.texture = static_cast<int>(textures_.size()) - 1;
      for (const cv::Point2d& c : foot) roof.outline.push_back(at_height(c, s.height_m));
      solid.faces.push_back(roof);
      for (const cv::Point2d& c : foot) {
        solid.corners.push_back(at_height(c, 0.0));
        solid.corners.push_back(at_height(c, s.height_m));
      }
    }
    solids_.push_back(std::move(solid));
  }
}

StructureRenderer::~StructureRenderer() = default;
StructureRenderer::StructureRenderer(StructureRenderer&&) noexcept = default;
StructureRenderer& StructureRenderer::operator=(StructureRenderer&&) noexcept = default;

bool StructureRenderer::empty() const { return solids_.empty(); }

std::vector<StructureTruth> StructureRenderer::render(cv::Mat& image, cv::Mat& id_mask, const cv::Matx34d& projection,
                                                      cv::Point3d camera) const {
  const cv::Rect frame(0, 0, image.cols, image.rows);
  const cv::Rect2d view(-0.5, -0.5, image.cols, image.rows);
  // Depth orders the structures; the silhouette decides whether one is in view at all.
  struct InView {
    double depth;
    const Solid* solid;
    std::vector<cv::Point2d> outline;
  };
  std::vector<InView> in_view;
  for (const Solid& solid : solids_) {
    std::vector<cv::Point2f> pts;
    bool in_front = true;
    for (const cv::Point3d& c : solid.corners) {
      double depth = 0.0;
      const cv::Point2d p = project(projection, c, depth);
      in_front = in_front && depth > 0.0;
      pts.emplace_back(static_cast<float>(p.x), static_cast<float>(p.y));
    }
    if (!in_front) continue;
    std::vector<cv::Point2f> hull;
    cv::convexHull(pts, hull);
    double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
    for (const cv::Point2f& p : hull) x0 = std::min<double>(x0, p.x), y0 = std::min<double>(y0, p.y), x1 = std::max<double>(x1, p.x), y1 = std::max<double>(y1, p.y);
    if ((cv::Rect2d(x0, y0, x1 - x0, y1 - y0) & view).area() <= 0.0) continue;
    double depth = 0.0;
    project(projection, solid.middle, depth);
    InView v{depth, &solid, {}};
    for (const cv::Point2f& p : hull) v.outline.emplace_back(p.x, p.y);
    in_view.push_back(std::move(v));
  }
  std::sort(in_view.begin(), in_view.end(), [](const InView& a, const InView& b) {
    return a.depth != b.depth ? a.depth > b.depth : a.solid->id < b.solid->id;  // farthest first
  });

  for (const InView& item : in_view) {
    for (const Face& face : item.solid->faces) {
      if (cv::norm(face.normal) > 0.0 && face.normal.dot(cv::Vec3d(camera - face.origin)) <= 0.0) continue;  // faces away
      std::vector<cv::Point2f> pts;
      double depth = 0.0;
      for (const cv::Point3d& c : face.outline) {
        const cv::Point2d p = project(projection, c, depth);
        pts.emplace_back(static_cast<float>(p.x), static_cast<float>(p.y));
      }
      if (face.hull) {
        std::vector<cv::Point2f> hull;
        cv::convexHull(pts, hull);
        pts = hull;
      }
      const cv::Rect bounds = cv::boundingRect(pts);
      const cv::Rect roi = cv::Rect(bounds.x - 1, bounds.y - 1, bounds.width + 2, bounds.height + 2) & frame;
      if (roi.empty()) continue;
      // Anti-aliased coverage of the face (1/16 px vertices), then its texture through the
      // plane's homography, both only over the face's bounding box.
      std::vector<cv::Point> poly;
      for (const cv::Point2f& p : pts)
        poly.emplace_back(static_cast<int>(std::lround((p.x - roi.x) * 16.0)), static_cast<int>(std::lround((p.y - roi.y) * 16.0)));
      cv::Mat coverage = cv::Mat::zeros(roi.size(), CV_8U);
      cv::fillPoly(coverage, std::vector<std::vector<cv::Point>>{poly}, cv::Scalar(255), cv::LINE_AA, 4);
      const cv::Vec4d o(face.origin.x, face.origin.y, face.origin.z, 1.0);
      const cv::Vec3d cu = projection * cv::Vec4d(face.u[0], face.u[1], face.u[2], 0.0);
      const cv::Vec3d cv_ = projection * cv::Vec4d(face.v[0], face.v[1], face.v[2], 0.0);
      const cv::Vec3d co = projection * o;
      const cv::Matx33d image_from_texture(cu[0] - roi.x * cu[2], cv_[0] - roi.x * cv_[2], co[0] - roi.x * co[2],
                                           cu[1] - roi.y * cu[2], cv_[1] - roi.y * cv_[2], co[1] - roi.y * co[2],
                                           cu[2], cv_[2], co[2]);
      cv::Mat patch;
      cv::warpPerspective(textures_[face.texture], patch, cv::Mat(image_from_texture), roi.size(), cv::INTER_LINEAR, cv::BORDER_REPLICATE);
      cv::Mat alpha;
      coverage.convertTo(alpha, CV_32F, 1.0 / 255.0);
      cv::Mat target = image(roi);
      cv::Mat blended = target + (patch * face.gain - target).mul(alpha);
      blended.copyTo(target);
      id_mask(roi).setTo(0, coverage >= 128);
    }
  }

  std::vector<StructureTruth> truth;
  for (const InView& item : in_view) {
    StructureTruth t;
    t.id = item.solid->id;
    t.kind = item.solid->kind;
    t.height_m = item.solid->height_m;
    t.outline = item.outline;
    truth.push_back(std::move(t));
  }
  std::sort(truth.begin(), truth.end(), [](const StructureTruth& a, const StructureTruth& b) { return a.id < b.id; });
  return truth;
}

}  // namespace uavmot::sim::detail
