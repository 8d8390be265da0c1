#include "frame_input.hpp"

#include <algorithm>
#include <cmath>

namespace uavmot::tracking {
namespace {

// Homographies this far from a similarity are treated as broken input rather than camera motion.
constexpr double kMinDeterminant = 1e-3;
constexpr double kMaxDeterminant = 1e3;

bool usable_homography(Homography& h) {
  if (!uavmot::is_finite(h) || !normalize_homography(h)) return false;
  const double det = cv::determinant(h);
  return std::isfinite(det) && std::abs(det) > kMinDeterminant && std::abs(det) < kMaxDeterminant;
}

bool method_selected(const std::string& choice, SegmentationMethod method, bool frame_has_fusion) {
  if (choice == "all") return true;
  if (choice == "auto") return !frame_has_fusion || method == SegmentationMethod::Fusion;
  return choice == to_string(method);
}

std::vector<OrientedBox> select_regions(const SegmentationResult& segmentation, const TrackerOptions& options,
                                        uint64_t& rejected) {
  const bool has_fusion = std::any_of(segmentation.regions.begin(), segmentation.regions.end(),
                                      [](const Region& r) { return r.method == SegmentationMethod::Fusion; });
  std::vector<OrientedBox> out;
  for (const auto& region : segmentation.regions) {
    if (!method_selected(options.region_method, region.method, has_fusion)) continue;
    const OrientedBox& b = region.box;
    if (!uavmot::is_finite(b) || b.width <= 0.0 || b.length <= 0.0) {
      ++rejected;
      continue;
    }
    if (box_area(b) < options.min_region_area_px) continue;
    OrientedBox normalized = b;
    normalized.angle_deg = normalize_axis_angle_deg(b.angle_deg);
    if (normalized.width > normalized.length) {  // keep the convention: length is the longer side
      std::swap(normalized.width, normalized.length);
      normalized.angle_deg = normalize_axis_angle_deg(normalized.angle_deg + 90.0);
    }
    out.push_back(normalized);
  }
  return out;
}

// This frame's valid features: the moving ones, and the stopped (no longer moving) ones that a track
// which has travelled MIN_TRAVEL_PX links to (a link made while they moved).
FeatureIndex select_features(const MotionEstimate& motion, const std::vector<TrackRecord>& tracks,
                             const TrackerOptions& options, double min_travel_px, uint64_t& rejected) {
  std::vector<uint64_t> linked;
  if (options.stopped_link_min_frames > 0) {
    for (const auto& t : tracks) {
      if (std::hypot(t.anchor_box.cx - t.origin.x, t.anchor_box.cy - t.origin.y) < min_travel_px) continue;
      for (const auto& link : t.features) linked.push_back(link.feature_id);
    }
    std::sort(linked.begin(), linked.end());
  }
  std::vector<TrackedFeature> moving;
  std::vector<TrackedFeature> stopped;
  for (const auto& f : motion.features) {
    if (!std::isfinite(f.position.x) || !std::isfinite(f.position.y) || !std::isfinite(f.velocity[0]) ||
        !std::isfinite(f.velocity[1])) {
      if (f.moving) ++rejected;
      continue;
    }
    if (f.moving) {
      moving.push_back(f);
    } else if (std::binary_search(linked.begin(), linked.end(), f.id)) {
      stopped.push_back(f);
    }
  }
  return FeatureIndex(std::move(moving), std::move(stopped), static_cast<uint32_t>(options.stopped_link_min_frames));
}

// The motion estimate carries the size of the frame it was estimated on; TrackerOptions' size is
// the fallback for input without one.
cv::Size image_size(const MotionEstimate& motion, const TrackerOptions& options) {
  if (motion.image_width > 0 && motion.image_height > 0) return {motion.image_width, motion.image_height};
  return {options.image_width, options.image_height};
}

}  // namespace

FrameInput read_frame_input(const MotionEstimate& motion, const SegmentationResult& segmentation,
                            const TrackerOptions& options, const SceneInfo& scene, TrackerState& state) {
  Homography h = motion.homography;
  if (!usable_homography(h)) {
    ++state.rejected_homographies;
    h = identity_homography();
  }
  std::vector<OrientedBox> regions = select_regions(segmentation, options, state.rejected_regions);
  const double min_travel_px = options.stopped_link_min_travel_lengths * scene.vehicle_length_m / scene.gsd_m;
  FeatureIndex features = select_features(motion, state.tracks, options, min_travel_px, state.rejected_features);
  return FrameInput{h, std::move(regions), std::move(features), image_size(motion, options)};
}

}  // namespace uavmot::tracking
