#include "feature_associator.hpp"

#include <algorithm>
#include <cmath>
#include <set>

#include "vector_angles.hpp"

namespace uavmot::tracking {
namespace {

double median_of(std::vector<double> values) {
  const size_t n = values.size();
  std::sort(values.begin(), values.end());
  return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

const TrackedFeature* find_by_id(const std::vector<TrackedFeature>& sorted, uint64_t id) {
  const auto it = std::lower_bound(sorted.begin(), sorted.end(), id,
                                   [](const TrackedFeature& f, uint64_t value) { return f.id < value; });
  return (it != sorted.end() && it->id == id) ? &*it : nullptr;
}

void sort_by_id(std::vector<TrackedFeature>& features) {
  std::stable_sort(features.begin(), features.end(),
                   [](const TrackedFeature& a, const TrackedFeature& b) { return a.id < b.id; });
}

}  // namespace

FeatureIndex::FeatureIndex(std::vector<TrackedFeature> moving, std::vector<TrackedFeature> stopped,
                           uint32_t stopped_link_min_frames)
    : features_(std::move(moving)), stopped_(std::move(stopped)), stopped_link_min_frames_(stopped_link_min_frames) {
  sort_by_id(features_);
  sort_by_id(stopped_);
  for (size_t i = 0; i < features_.size(); ++i) {
    grid_.insert(static_cast<int>(i), cv::Rect2d(features_[i].position.x, features_[i].position.y, 0.0, 0.0));
  }
}

const TrackedFeature* FeatureIndex::find(uint64_t id) const { return find_by_id(features_, id); }

const TrackedFeature* FeatureIndex::find_linked(const FeatureLink& link) const {
  if (const TrackedFeature* f = find_by_id(features_, link.feature_id)) return f;
  if (stopped_link_min_frames_ == 0 || link.frames_linked < stopped_link_min_frames_) return nullptr;
  return find_by_id(stopped_, link.feature_id);
}

std::vector<int> FeatureIndex::inside(const OrientedBox& box) const {
  const BoxFrame frame(box);
  std::vector<int> out;
  for (const int i : grid_.query(axis_aligned_bounds(box))) {
    if (frame.contains(features_[static_cast<size_t>(i)].position)) out.push_back(i);
  }
  return out;
}

cv::Vec2d median_velocity(const std::vector<cv::Vec2d>& velocities) {
  if (velocities.empty()) return {0.0, 0.0};
  std::vector<double> xs;
  std::vector<double> ys;
  for (const auto& v : velocities) {
    xs.push_back(v[0]);
    ys.push_back(v[1]);
  }
  return {median_of(xs), median_of(ys)};
}

bool similar_motion(const cv::Vec2d& v, const cv::Vec2d& reference, const TrackerOptions& options) {
  const double ref_speed = cv::norm(reference);
  const double tolerance = std::max(options.feature_motion_abs_tolerance, options.feature_motion_rel_tolerance * ref_speed);
  if (cv::norm(v - reference) > tolerance) return false;
  if (ref_speed < options.feature_min_speed_for_direction) return true;
  if (cv::norm(v) <= 0.0) return false;
  return angle_between_deg(v, reference) <= options.feature_direction_tolerance_deg;
}

cv::Point2d centre_from_feature(const OrientedBox& box, const FeatureLink& link, const cv::Point2d& position) {
  const cv::Point2d offset = from_box_coordinates(box, link.box_uv) - cv::Point2d(box.cx, box.cy);
  return position - offset;
}

void prune_feature_links(TrackRecord& track, const OrientedBox& predicted, const cv::Vec2d& track_velocity,
                         bool velocity_known, const FeatureIndex& features, const TrackerOptions& options) {
  const double limit = 0.5 + options.feature_position_margin;
  std::vector<FeatureLink> kept;
  std::vector<const TrackedFeature*> kept_features;
  for (const auto& link : track.features) {
    const TrackedFeature* f = features.find_linked(link);
    if (f == nullptr) continue;  // vanished or no longer moving
    const cv::Point2d uv = to_box_coordinates(predicted, f->position);
    if (std::abs(uv.x) > limit || std::abs(uv.y) > limit) continue;
    kept.push_back(link);
    kept_features.push_back(f);
  }
  if (kept.empty()) {
    track.features.clear();
    return;
  }
  // Motion outliers: against the track's velocity once it is known, else against the links' median.
  std::vector<cv::Vec2d> velocities;
  for (const auto* f : kept_features) velocities.push_back(f->velocity);
  const cv::Vec2d reference = velocity_known ? track_velocity : median_velocity(velocities);
  // Position outliers: centre estimates far from their median.
  std::vector<double> cxs;
  std::vector<double> cys;
  std::vector<cv::Point2d> centres;
  for (size_t i = 0; i < kept.size(); ++i) {
    centres.push_back(centre_from_feature(predicted, kept[i], kept_features[i]->position));
    cxs.push_back(centres.back().x);
    cys.push_back(centres.back().y);
  }
  const cv::Point2d median_centre(median_of(cxs), median_of(cys));
  track.features.clear();
  for (size_t i = 0; i < kept.size(); ++i) {
    if (!similar_motion(kept_features[i]->velocity, reference, options)) continue;
    if (kept.size() >= 3 && cv::norm(centres[i] - median_centre) > options.feature_reconstruction_outlier_px) continue;
    track.features.push_back(kept[i]);
  }
}

std::optional<cv::Point2d> reconstruct_centre(const TrackRecord& track, const OrientedBox& predicted,
                                              const FeatureIndex& features, int min_features) {
  std::vector<double> cxs;
  std::vector<double> cys;
  for (const auto& link : track.features) {
    const TrackedFeature* f = features.find_linked(link);
    if (f == nullptr) continue;
    const cv::Point2d c = centre_from_feature(predicted, link, f->position);
    cxs.push_back(c.x);
    cys.push_back(c.y);
  }
  if (static_cast<int>(cxs.size()) < min_features || cxs.empty()) return std::nullopt;
  return cv::Point2d(median_of(cxs), median_of(cys));
}

std::vector<const TrackedFeature*> linked_features(const TrackRecord& track, const FeatureIndex& features) {
  std::vector<const TrackedFeature*> linked;
  for (const auto& link : track.features) {
    if (const TrackedFeature* f = features.find_linked(link)) linked.push_back(f);
  }
  return linked;
}

std::optional<cv::Vec2d> median_velocity_of(const std::vector<const TrackedFeature*>& linked, int min_features) {
  if (static_cast<int>(linked.size()) < min_features || linked.empty()) return std::nullopt;
  std::vector<cv::Vec2d> velocities;
  for (const TrackedFeature* f : linked) velocities.push_back(f->velocity);
  return median_velocity(velocities);
}

std::optional<cv::Vec2d> linked_velocity(const TrackRecord& track, const FeatureIndex& features, int min_features) {
  return median_velocity_of(linked_features(track, features), min_features);
}

namespace {

// Where criteria 2 and 3 look for a track's new features.
OrientedBox search_area(const TrackInFrame& track, const TrackerOptions& options, double min_length_px) {
  OrientedBox area = track.predicted;
  const bool under_way = track.velocity_known && cv::norm(track.velocity) >= options.heading_min_speed_px;
  if (under_way && area.length < min_length_px) area.length = min_length_px;
  return area;
}

}  // namespace

void link_new_features(std::vector<TrackInFrame>& tracks, const FeatureIndex& features, const TrackerOptions& options,
                       double min_search_length_px) {
  const size_t max_links = static_cast<size_t>(options.max_features_per_track);
  // Criterion 1: features linked to any track are taken.
  std::set<uint64_t> taken;
  for (const auto& t : tracks) {
    for (const auto& link : t.record.features) taken.insert(link.feature_id);
  }
  // How many predictions contain each feature (criteria 2 and 3).
  std::vector<int> containing(features.all().size(), 0);
  std::vector<std::vector<int>> inside_of_track(tracks.size());
  for (size_t t = 0; t < tracks.size(); ++t) {
    inside_of_track[t] = features.inside(search_area(tracks[t], options, min_search_length_px));
    for (const int i : inside_of_track[t]) ++containing[static_cast<size_t>(i)];
  }
  for (size_t t = 0; t < tracks.size(); ++t) {
    std::vector<FeatureLink>& links = tracks[t].record.features;
    if (!tracks[t].region_hit || links.size() >= max_links) continue;
    std::vector<const TrackedFeature*> candidates;
    for (const int i : inside_of_track[t]) {
      const TrackedFeature& f = features.all()[static_cast<size_t>(i)];
      if (containing[static_cast<size_t>(i)] == 1 && !taken.count(f.id)) candidates.push_back(&f);
    }
    if (candidates.empty()) continue;
    cv::Vec2d reference = tracks[t].velocity;
    if (!tracks[t].velocity_known) {
      std::vector<cv::Vec2d> vs;
      for (const auto* f : candidates) vs.push_back(f->velocity);
      reference = median_velocity(vs);
    }
    // Longer-lived features first: they are the likeliest to stay with the object.
    std::stable_sort(candidates.begin(), candidates.end(),
                     [](const TrackedFeature* a, const TrackedFeature* b) { return a->age > b->age; });
    for (const auto* f : candidates) {
      if (links.size() >= max_links) break;
      if (!similar_motion(f->velocity, reference, options)) continue;
      links.push_back(FeatureLink{f->id, to_box_coordinates(tracks[t].posterior, f->position), 0});
      taken.insert(f->id);
    }
    std::sort(links.begin(), links.end(),
              [](const FeatureLink& a, const FeatureLink& b) { return a.feature_id < b.feature_id; });
  }
}

void refresh_feature_links(TrackRecord& track, const OrientedBox& posterior, const FeatureIndex& features,
                           double smoothing) {
  for (auto& link : track.features) {
    const TrackedFeature* f = features.find_linked(link);
    if (f == nullptr) continue;
    const cv::Point2d uv = to_box_coordinates(posterior, f->position);
    link.box_uv = (1.0 - smoothing) * link.box_uv + smoothing * uv;
    ++link.frames_linked;
  }
}

}  // namespace uavmot::tracking
