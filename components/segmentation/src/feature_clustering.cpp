#include "uavmot/segmentation/feature_clustering.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <opencv2/imgproc.hpp>

#include "uavmot/core/image_bounds.hpp"

namespace uavmot::segmentation {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Union-find with path halving; the smaller index becomes the root so results never depend
// on the order in which links are found.
class DisjointSets {
 public:
  explicit DisjointSets(size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), size_t{0}); }
  size_t find(size_t i) {
    while (parent_[i] != i) {
      parent_[i] = parent_[parent_[i]];
      i = parent_[i];
    }
    return i;
  }
  void unite(size_t a, size_t b) {
    a = find(a);
    b = find(b);
    if (a == b) return;
    if (a < b) parent_[b] = a; else parent_[a] = b;
  }

 private:
  std::vector<size_t> parent_;
};

bool usable(const TrackedFeature& f) {
  return std::isfinite(f.position.x) && std::isfinite(f.position.y) && std::isfinite(f.velocity[0]) &&
         std::isfinite(f.velocity[1]);
}

}  // namespace

LinkThresholds link_thresholds(const ClusteringOptions& options, const SceneInfo& scene) {
  LinkThresholds t;
  t.distance_px = scene.metres_to_px(options.link_distance_m);
  // m/s -> px/frame
  t.velocity_px_per_frame = options.link_speed_difference_mps / (scene.gsd_m * scene.fps);
  return t;
}

OrientedBox box_around_features(const std::vector<cv::Point2d>& points, const cv::Vec2d& mean_velocity,
                                double min_length_px, double min_width_px) {
  OrientedBox box;
  if (points.empty()) return box;
  double angle = 0.0;  // radians, of the length axis
  const double speed = std::hypot(mean_velocity[0], mean_velocity[1]);
  if (speed > 1e-9) {
    angle = std::atan2(mean_velocity[1], mean_velocity[0]);
  } else if (points.size() >= 2) {
    std::vector<cv::Point2f> pts;
    for (const auto& p : points) pts.emplace_back(static_cast<float>(p.x), static_cast<float>(p.y));
    angle = oriented_box_from_rotated_rect(cv::minAreaRect(pts)).angle_deg * kPi / 180.0;
  }
  const cv::Point2d along(std::cos(angle), std::sin(angle));
  const cv::Point2d across(-along.y, along.x);
  double a_min = 1e300, a_max = -1e300, c_min = 1e300, c_max = -1e300;
  for (const auto& p : points) {
    const double a = p.dot(along), c = p.dot(across);
    a_min = std::min(a_min, a);
    a_max = std::max(a_max, a);
    c_min = std::min(c_min, c);
    c_max = std::max(c_max, c);
  }
  const double a_mid = 0.5 * (a_min + a_max), c_mid = 0.5 * (c_min + c_max);
  const cv::Point2d centre = along * a_mid + across * c_mid;
  box.cx = centre.x;
  box.cy = centre.y;
  box.length = std::max(a_max - a_min, min_length_px);
  box.width = std::max(c_max - c_min, min_width_px);
  box.angle_deg = normalize_axis_angle_deg(angle * 180.0 / kPi);
  return box;
}

std::vector<FeatureCluster> cluster_moving_features(const std::vector<TrackedFeature>& features,
                                                    const ClusteringOptions& options, const SceneInfo& scene,
                                                    cv::Size image_size, ClusteringStats* stats) {
  ClusteringStats local;
  std::vector<const TrackedFeature*> moving;
  for (const auto& f : features) {
    if (!f.moving) continue;
    ++local.moving_features;
    if (!usable(f)) {
      ++local.skipped_non_finite;
      continue;
    }
    if (image_size.width > 0 && image_size.height > 0 && !inside_image(f.position, image_size)) {
      ++local.skipped_outside;
      continue;
    }
    moving.push_back(&f);
  }

  const LinkThresholds t = link_thresholds(options, scene);
  const double sigma_factor = options.velocity_sigma_factor;
  std::vector<size_t> by_x(moving.size());
  std::iota(by_x.begin(), by_x.end(), size_t{0});
  std::stable_sort(by_x.begin(), by_x.end(),
                   [&](size_t a, size_t b) { return moving[a]->position.x < moving[b]->position.x; });

  // Sweep along x: only pairs closer than the link distance in x can be linked.
  DisjointSets sets(moving.size());
  for (size_t i = 0; i < by_x.size(); ++i) {
    const TrackedFeature& a = *moving[by_x[i]];
    for (size_t j = i + 1; j < by_x.size(); ++j) {
      const TrackedFeature& b = *moving[by_x[j]];
      if (b.position.x - a.position.x > t.distance_px) break;
      if (cv::norm(a.position - b.position) > t.distance_px) continue;
      const double noise = sigma_factor * std::hypot(a.velocity_sigma, b.velocity_sigma);
      const double velocity_limit = std::max(t.velocity_px_per_frame, std::isfinite(noise) ? noise : 0.0);
      if (cv::norm(a.velocity - b.velocity) > velocity_limit) continue;
      sets.unite(by_x[i], by_x[j]);
    }
  }

  std::vector<std::vector<size_t>> groups;
  std::vector<long> group_of_root(moving.size(), -1);
  for (size_t i = 0; i < moving.size(); ++i) {
    const size_t root = sets.find(i);
    if (group_of_root[root] < 0) {
      group_of_root[root] = static_cast<long>(groups.size());
      groups.emplace_back();
    }
    groups[static_cast<size_t>(group_of_root[root])].push_back(i);
  }

  struct Candidate {
    uint64_t min_id;
    size_t first_index;
    FeatureCluster cluster;
  };
  std::vector<Candidate> candidates;
  const double min_length = scene.metres_to_px(scene.vehicle_length_m);
  const double min_width = scene.metres_to_px(scene.vehicle_width_m);
  for (const auto& group : groups) {
    if (static_cast<int>(group.size()) < options.min_features) {
      ++local.dropped_small_clusters;
      continue;
    }
    Candidate c{UINT64_MAX, group.front(), {}};
    std::vector<cv::Point2d> points;
    cv::Vec2d velocity_sum(0.0, 0.0);
    for (size_t i : group) {
      const TrackedFeature& f = *moving[i];
      points.push_back(f.position);
      velocity_sum += f.velocity;
      c.min_id = std::min(c.min_id, f.id);
      c.cluster.feature_ids.push_back(f.id);
    }
    c.cluster.velocity = velocity_sum * (1.0 / static_cast<double>(group.size()));
    c.cluster.box = box_around_features(points, c.cluster.velocity, min_length, min_width);
    std::sort(c.cluster.feature_ids.begin(), c.cluster.feature_ids.end());
    candidates.push_back(std::move(c));
  }
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
    return a.min_id != b.min_id ? a.min_id < b.min_id : a.first_index < b.first_index;
  });

  std::vector<FeatureCluster> clusters;
  clusters.reserve(candidates.size());
  for (auto& c : candidates) {
    c.cluster.id = static_cast<uint32_t>(clusters.size() + 1);
    clusters.push_back(std::move(c.cluster));
  }
  if (stats) *stats = local;
  return clusters;
}

}  // namespace uavmot::segmentation
