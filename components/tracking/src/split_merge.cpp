#include "split_merge.hpp"

#include <algorithm>
#include <set>

#include <opencv2/imgproc.hpp>

#include "updater.hpp"

namespace uavmot::tracking {

bool region_motion(const OrientedBox& box, const FeatureIndex& features, cv::Vec2d& velocity) {
  std::vector<cv::Vec2d> vs;
  for (const int i : features.inside(box)) vs.push_back(features.all()[static_cast<size_t>(i)].velocity);
  if (vs.empty()) return false;
  velocity = median_velocity(vs);
  return true;
}

ObjectLimits object_limits(const TrackerOptions& options, const SceneInfo& scene) {
  ObjectLimits limits;
  limits.single_object = cv::Size2d(scene.metres_to_px(scene.vehicle_width_m) * options.single_object_size_factor,
                                    scene.metres_to_px(scene.vehicle_length_m) * options.single_object_size_factor);
  limits.largest_object = cv::Size2d(scene.metres_to_px(options.max_object_width_m),
                                     scene.metres_to_px(scene.vehicle_length_m) * options.max_object_length_factor);
  limits.widest_region = scene.metres_to_px(options.max_region_width_m);
  return limits;
}

OrientedBox within_lane_of(const OrientedBox& region, const OrientedBox& predicted) {
  const OrientedBox along = box_along_heading(region, predicted.angle_deg);
  const double a = predicted.angle_deg * CV_PI / 180.0;
  const cv::Point2d axis(std::cos(a), std::sin(a)), normal(-std::sin(a), std::cos(a));
  const cv::Point2d offset(along.cx - predicted.cx, along.cy - predicted.cy);
  const double u = offset.dot(axis), v = offset.dot(normal);
  double lo = std::max(v - along.width / 2.0, -predicted.width / 2.0);
  double hi = std::min(v + along.width / 2.0, predicted.width / 2.0);
  if (hi <= lo) lo = -predicted.width / 2.0, hi = predicted.width / 2.0;
  const double mid = (lo + hi) / 2.0;
  return OrientedBox{predicted.cx + u * axis.x + mid * normal.x, predicted.cy + u * axis.y + mid * normal.y, hi - lo,
                     along.length, along.angle_deg};
}

OrientedBox enclosing_box(const std::vector<OrientedBox>& boxes) {
  std::vector<cv::Point2f> corners;
  for (const auto& b : boxes) {
    for (const auto& c : box_corners(b)) corners.emplace_back(static_cast<float>(c.x), static_cast<float>(c.y));
  }
  return oriented_box_from_rotated_rect(cv::minAreaRect(corners));
}

namespace {

// How many of the track's linked features lie inside `box`.
int linked_features_inside(const TrackRecord& track, const OrientedBox& box, const FeatureIndex& features) {
  const BoxFrame frame(box);
  int n = 0;
  for (const auto& link : track.features) {
    const TrackedFeature* f = features.find_linked(link);
    if (f != nullptr && frame.contains(f->position)) ++n;
  }
  return n;
}

// True when `box` is wider or longer than `limit` (width across, height along; zero = no limit).
bool larger_than(const OrientedBox& box, const cv::Size2d& limit) {
  return limit.width > 0.0 && limit.height > 0.0 && (box.width > limit.width || box.length > limit.height);
}

// The fragments' union fits the predicted object enlarged by `factor`, and no vehicle is larger than
// `largest`: without that bound a box that took in its neighbour in a queue would take in the next
// one too, growing a little every frame.
bool fits_inside(const OrientedBox& candidate, const OrientedBox& predicted, double factor, const cv::Size2d& largest) {
  const double big = std::max(predicted.length, predicted.width) * factor;
  const double small = std::min(predicted.length, predicted.width) * factor;
  if (larger_than(candidate, largest)) return false;
  return candidate.length <= big && candidate.width <= std::max(small, 1.0) + 1.0;
}

// Split handling for one track and the regions only it validates (`own`, with their boxes).
TrackMeasurement split_measurement(const TrackInFrame& track, const std::vector<int>& own,
                                   const std::vector<OrientedBox>& boxes, const std::vector<double>& overlaps,
                                   const FeatureIndex& features, const TrackerOptions& options,
                                   const cv::Size2d& largest_object_px, std::vector<int>& leftovers) {
  TrackMeasurement m;
  m.kind = MeasurementKind::Box;
  if (own.size() == 1) {
    m.box = boxes[0];
    return m;
  }
  // Primary region: the one the track's features follow; ties go to the larger overlap.
  size_t primary = 0;
  int best_links = -1;
  double best_overlap = -1.0;
  for (size_t i = 0; i < own.size(); ++i) {
    const int links = linked_features_inside(track.record, boxes[i], features);
    if (links > best_links || (links == best_links && overlaps[i] > best_overlap)) {
      primary = i;
      best_links = links;
      best_overlap = overlaps[i];
    }
  }
  cv::Vec2d primary_motion;
  const bool primary_known = region_motion(boxes[primary], features, primary_motion);
  std::vector<OrientedBox> parts = {boxes[primary]};
  for (size_t i = 0; i < own.size(); ++i) {
    if (i == primary) continue;
    const OrientedBox& candidate = boxes[i];
    cv::Vec2d motion;
    const bool known = region_motion(candidate, features, motion);
    const bool same_motion = !(known && primary_known) || similar_motion(motion, primary_motion, options);
    std::vector<OrientedBox> grown = parts;
    grown.push_back(candidate);
    const OrientedBox union_box = enclosing_box(grown);
    if (same_motion && fits_inside(union_box, track.predicted, options.fragment_union_factor, largest_object_px)) {
      parts = std::move(grown);  // a fragment of the same object
    } else {
      leftovers.push_back(own[i]);
      m.size_jump = true;
    }
  }
  m.box = parts.size() == 1 ? parts.front() : enclosing_box(parts);
  return m;
}

}  // namespace

namespace {

// A tentative track never turns an established track's region into a merge: where a region validates
// both, the tentative track's claim is dropped (it then misses and is deleted if it was spurious).
RegionAssociation without_tentative_claims(const RegionAssociation& association, const std::vector<TrackInFrame>& tracks) {
  RegionAssociation out = association;
  for (auto& claimants : out.tracks_of_region) {
    const bool has_established = std::any_of(claimants.begin(), claimants.end(), [&](int t) {
      return tracks[static_cast<size_t>(t)].record.state != TrackState::Tentative;
    });
    if (!has_established || claimants.size() < 2) continue;
    std::erase_if(claimants, [&](int t) { return tracks[static_cast<size_t>(t)].record.state == TrackState::Tentative; });
  }
  for (size_t t = 0; t < tracks.size(); ++t) {
    auto& regs = out.regions_of_track[t];
    auto& overlaps = out.overlap_of_track[t];
    for (size_t i = regs.size(); i-- > 0;) {
      const auto& claimants = out.tracks_of_region[static_cast<size_t>(regs[i])];
      if (!std::binary_search(claimants.begin(), claimants.end(), static_cast<int>(t))) {
        regs.erase(regs.begin() + static_cast<std::ptrdiff_t>(i));
        overlaps.erase(overlaps.begin() + static_cast<std::ptrdiff_t>(i));
      }
    }
  }
  return out;
}

// True when `a` is the track that keeps a region over `b`: more region hits, then the lower id.
bool senior(const TrackRecord& a, const TrackRecord& b) { return a.hits != b.hits ? a.hits > b.hits : a.id < b.id; }

// A shared region no larger than one object, whose tracks move alike, holds one object that was
// tracked in pieces (over-segmentation at its first frames): the senior track keeps the region and
// the others, if it was all they saw, are absorbed.
// Sets absorbed[t] for the absorbed tracks and keepers[t] for the tracks that keep such a region.
void absorb_pieces(RegionAssociation& association, const std::vector<OrientedBox>& regions,
                   const std::vector<TrackInFrame>& tracks, const ObjectLimits& limits, const TrackerOptions& options,
                   std::vector<bool>& absorbed, std::vector<bool>& keepers) {
  if (limits.single_object.width <= 0.0 || limits.single_object.height <= 0.0) return;
  for (size_t r = 0; r < regions.size(); ++r) {
    auto& claimants = association.tracks_of_region[r];
    if (claimants.size() < 2) continue;
    if (larger_than(regions[r], limits.single_object)) continue;
    // The tracks themselves must fit in one object too: two cars side by side at one speed may both
    // claim a small blob between them, and neither is a piece of the other.
    std::vector<OrientedBox> claimed;
    for (const int t : claimants) claimed.push_back(tracks[static_cast<size_t>(t)].predicted);
    if (larger_than(enclosing_box(claimed), limits.largest_object)) continue;
    size_t keeper = static_cast<size_t>(claimants.front());
    for (const int t : claimants) {
      if (senior(tracks[static_cast<size_t>(t)].record, tracks[keeper].record)) keeper = static_cast<size_t>(t);
    }
    const bool alike = std::all_of(claimants.begin(), claimants.end(), [&](int t) {
      return similar_motion(tracks[static_cast<size_t>(t)].velocity, tracks[keeper].velocity, options);
    });
    if (!alike) continue;
    for (const int t : claimants) {
      if (static_cast<size_t>(t) == keeper) continue;
      auto& regs = association.regions_of_track[static_cast<size_t>(t)];
      auto& overlaps = association.overlap_of_track[static_cast<size_t>(t)];
      const auto it = std::find(regs.begin(), regs.end(), static_cast<int>(r));
      overlaps.erase(overlaps.begin() + (it - regs.begin()));
      regs.erase(it);
      if (regs.empty()) absorbed[static_cast<size_t>(t)] = true;
    }
    claimants = {static_cast<int>(keeper)};
    keepers[keeper] = true;
  }
}

}  // namespace

SplitMergeResult resolve_split_merge(const RegionAssociation& gating, const std::vector<OrientedBox>& regions,
                                     const std::vector<TrackInFrame>& tracks, const FeatureIndex& features,
                                     const TrackerOptions& options, const ObjectLimits& limits) {
  RegionAssociation association = without_tentative_claims(gating, tracks);
  SplitMergeResult result;
  result.measurements.resize(tracks.size());
  result.absorbed.assign(tracks.size(), false);
  std::vector<bool> keepers(tracks.size(), false);
  absorb_pieces(association, regions, tracks, limits, options, result.absorbed, keepers);
  std::vector<int> leftovers;
  for (size_t t = 0; t < tracks.size(); ++t) {
    const auto& candidates = association.regions_of_track[t];
    if (candidates.empty()) continue;
    std::vector<int> own;
    std::vector<double> own_overlaps;
    for (size_t i = 0; i < candidates.size(); ++i) {
      if (association.tracks_of_region[static_cast<size_t>(candidates[i])].size() == 1) {
        own.push_back(candidates[i]);
        own_overlaps.push_back(association.overlap_of_track[t][i]);
      }
    }
    if (!own.empty()) {
      // A region wider than any vehicle holds this track's object and an untracked neighbour.
      std::vector<OrientedBox> own_boxes;
      for (const int r : own) {
        const OrientedBox& region = regions[static_cast<size_t>(r)];
        // Read along the track's axis, as the update reads it: a blob across the lane is wide too.
        const bool too_wide = limits.widest_region > 0.0 &&
                              box_along_heading(region, tracks[t].predicted.angle_deg).width > limits.widest_region;
        own_boxes.push_back(too_wide ? within_lane_of(region, tracks[t].predicted) : region);
      }
      result.measurements[t] = split_measurement(tracks[t], own, own_boxes, own_overlaps, features, options,
                                                 limits.largest_object, leftovers);
      result.measurements[t].size_jump = result.measurements[t].size_jump || keepers[t];
      continue;
    }
    // Merge: every region this track sees is shared with another track.
    TrackMeasurement m;
    m.merged = true;
    if (const auto centre = reconstruct_centre(tracks[t].record, tracks[t].predicted, features,
                                               options.min_reconstruction_features)) {
      m.kind = MeasurementKind::Centre;
      m.centre = *centre;
    }
    result.measurements[t] = m;
  }
  for (size_t r = 0; r < regions.size(); ++r) {
    if (association.tracks_of_region[r].empty()) result.free_regions.push_back(static_cast<int>(r));
  }
  result.free_regions.insert(result.free_regions.end(), leftovers.begin(), leftovers.end());
  std::sort(result.free_regions.begin(), result.free_regions.end());
  result.free_regions.erase(std::unique(result.free_regions.begin(), result.free_regions.end()), result.free_regions.end());
  return result;
}

}  // namespace uavmot::tracking
