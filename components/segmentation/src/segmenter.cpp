#include "uavmot/segmentation/segmenter.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>

#include <opencv2/imgproc.hpp>

#include "uavmot/core/error.hpp"
#include "uavmot/segmentation/blob_regions.hpp"
#include "feature_recentring.hpp"
#include "method_gradients.hpp"
#include "motion_evidence.hpp"
#include "shift_check.hpp"

namespace uavmot::segmentation {
namespace {

void validate_scene(const SceneInfo& s) {
  auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  if (!positive(s.gsd_m) || !positive(s.fps) || !positive(s.vehicle_length_m) || !positive(s.vehicle_width_m)) {
    throw InvalidArgument("segmentation: scene gsd_m, fps, vehicle_length_m and vehicle_width_m must be positive");
  }
}

// Peak of an accumulator over a vertical step of `contrast` grey levels.
template <typename Gradient>
double step_response(double contrast, Gradient gradient) {
  cv::Mat step(32, 32, CV_8U, cv::Scalar(0));
  step(cv::Rect(16, 0, 16, 32)).setTo(cv::Scalar(std::clamp(std::round(contrast), 1.0, 255.0)));
  double peak = 0.0;
  cv::minMaxLoc(gradient(step), nullptr, &peak);
  return peak > 0.0 ? peak : 1.0;
}

bool crop_usable(const ImageCrop& crop) {
  return !crop.pixels.empty() && (crop.pixels.type() == CV_8UC1 || crop.pixels.type() == CV_8UC3) &&
         crop.pixels.cols == crop.roi.width && crop.pixels.rows == crop.roi.height;
}

Region cluster_region(const FeatureCluster& cluster) {
  Region region;
  region.box = cluster.box;
  region.method = SegmentationMethod::Clustering;
  region.score = 1.0;
  region.cluster_id = static_cast<int32_t>(cluster.id);
  return region;
}

size_t fused_methods() {
  size_t n = 0;
  for (SegmentationMethod method : kSegmentationMethods) n += method_gradient(method).fused ? 1 : 0;
  return n;
}

// Fraction of `candidate`'s area covered by `kept`.
double covered_fraction(const OrientedBox& candidate, const OrientedBox& kept) {
  const double area = box_area(candidate);
  return area > 0.0 ? intersection_area(candidate, kept) / area : 1.0;
}

// `box` moved `along` px along its length axis and `across` px across it (+ toward its +y side).
OrientedBox moved_in_own_frame(OrientedBox box, double along, double across) {
  const double a = box.angle_deg * CV_PI / 180.0;
  box.cx += along * std::cos(a) - across * std::sin(a);
  box.cy += along * std::sin(a) + across * std::cos(a);
  return box;
}

// Steps of moving a blob-less cluster's box onto its motion evidence: from one end of a car, the
// first step falls short, as the far end's evidence lies mostly outside the search. 1 step against
// 3 (docs/segmentation.md, "Blob-less clusters"): `paper` seed 103 92.1 against 92.5 % correct,
// 1.94 against 1.19 false alarms per frame.
constexpr int kEvidenceSteps = 3;

// A blob-less cluster's box moved onto its motion evidence, searched `lengthen_px` past each end and
// `margin_px` each side, kEvidenceSteps times, if it then moves with the cluster (the shift check);
// reported with the segmentation's `method`, since the image placed it.
std::optional<Region> region_on_evidence(const FeatureCluster& cluster, const ImageCrop& current, const ShiftSearch& search,
                                         const Homography& previous_from_current, const std::vector<ImageCrop>& previous,
                                         double margin_px, double lengthen_px, double max_ratio,
                                         SegmentationMethod method) {
  Region region = cluster_region(cluster);
  for (int k = 0; k < kEvidenceSteps; ++k) {
    const auto e = motion_evidence(current, region.box, margin_px, search, previous_from_current, previous, lengthen_px);
    if (!e) {
      if (k == 0) return std::nullopt;
      break;
    }
    region.box = moved_in_own_frame(region.box, e->along_px, e->across_px);
  }
  const auto moved = compare_shifts(current, region.box, search, previous_from_current, previous);
  if (!moved || moved->moving_error > max_ratio * moved->static_error) return std::nullopt;
  region.method = method;
  return region;
}

}  // namespace

bool Segmenter::within_vehicle_size(const OrientedBox& box) const {
  const auto& r = options_.regions;
  return !(box.length > r.max_length_factor * scene_.metres_to_px(scene_.vehicle_length_m) ||
           box.width > r.max_width_factor * scene_.metres_to_px(scene_.vehicle_width_m));
}

std::optional<Region> Segmenter::uncovered_features_region(const FeatureCluster& cluster,
                                                           const std::vector<cv::Point2d>& feature_positions,
                                                           const std::vector<Region>& regions) const {
  // Features within half a vehicle width of a region are its own (corners on the outline).
  const double margin = options_.regions.support_margin_px + 0.5 * scene_.metres_to_px(scene_.vehicle_width_m);
  std::vector<cv::Point2d> uncovered;
  for (const auto& p : feature_positions) {
    const bool covered = std::any_of(regions.begin(), regions.end(), [&](const Region& r) {
      OrientedBox grown = r.box;
      grown.length += 2.0 * margin;
      grown.width += 2.0 * margin;
      return box_contains(grown, p);
    });
    if (!covered) uncovered.push_back(p);
  }
  if (static_cast<int>(uncovered.size()) < std::max(2, options_.clustering.min_features)) return std::nullopt;
  Region region = cluster_region(cluster);
  region.box = box_around_features(uncovered, cluster.velocity, scene_.metres_to_px(scene_.vehicle_length_m),
                                   scene_.metres_to_px(scene_.vehicle_width_m));
  region.score = static_cast<double>(uncovered.size()) / static_cast<double>(feature_positions.size());
  return region;
}

SegmentationInput make_segmentation_input(const Frame& frame, const std::vector<cv::Rect>& rois) {
  SegmentationInput input;
  input.stream_id = frame.stream_id;
  input.frame_index = frame.index;
  input.capture_time_ns = frame.capture_time_ns;
  input.image_size = frame.image.size();
  const cv::Rect image(0, 0, frame.image.cols, frame.image.rows);
  for (const cv::Rect& roi : rois) {
    const cv::Rect clipped = roi & image;
    if (clipped.empty()) continue;
    input.crops.push_back({clipped, frame.image(clipped)});
  }
  return input;
}

namespace {
SegmentationOptions validated(SegmentationOptions o) {
  validate(o);
  return o;
}
SceneInfo validated(SceneInfo s) {
  validate_scene(s);
  return s;
}
ShadowOffsetOptions shadow_options(const RegionOptions& r, const SceneInfo& scene) {
  ShadowOffsetOptions o;
  o.max_offset_px = r.shadow_correction_factor > 0.0 ? scene.metres_to_px(r.shadow_max_m) : 0.0;
  o.bright_margin = r.shadow_bright_margin;
  o.min_regions = r.shadow_min_regions;
  o.agreement_px = r.shadow_agreement_px;
  o.min_darkness = r.shadow_min_darkness;
  return o;
}
}  // namespace

Segmenter::Segmenter(SegmentationOptions options, SceneInfo scene)
    : options_(validated(std::move(options))), scene_(validated(scene)), shadow_(shadow_options(options_.regions, scene_)) {
  references_.fill(1.0);
  for (SegmentationMethod method : kSegmentationMethods) {
    if (const Gradient gradient = method_gradient(method).gradient) {
      references_[static_cast<size_t>(method)] = step_response(
          options_.regions.min_edge_contrast, [&](const cv::Mat& m) { return gradient(m, options_.gradients); });
    }
  }
}

std::vector<FeatureCluster> Segmenter::cluster(const MotionEstimate& motion, cv::Size image_size,
                                               ClusteringStats* stats) const {
  return cluster_moving_features(motion.features, options_.clustering, scene_, image_size, stats);
}

cv::Rect Segmenter::window_of(const FeatureCluster& cluster, cv::Size image_size) const {
  const cv::Rect2d bounds = axis_aligned_bounds(cluster.box);
  const double margin = scene_.metres_to_px(options_.regions.window_margin_m);
  // Pixel i covers [i - 0.5, i + 0.5): the window holds every pixel touching the grown bounds.
  const int x0 = static_cast<int>(std::floor(bounds.x - margin + 0.5));
  const int y0 = static_cast<int>(std::floor(bounds.y - margin + 0.5));
  const int x1 = static_cast<int>(std::ceil(bounds.x + bounds.width + margin - 0.5));
  const int y1 = static_cast<int>(std::ceil(bounds.y + bounds.height + margin - 0.5));
  return cv::Rect(x0, y0, x1 - x0 + 1, y1 - y0 + 1) & cv::Rect(0, 0, image_size.width, image_size.height);
}

double Segmenter::evidence_lengthen_px() const {
  return options_.regions.fallback_evidence_lengths * scene_.metres_to_px(scene_.vehicle_length_m);
}

cv::Rect Segmenter::evidence_window_of(const cv::Rect& window, cv::Size image_size) const {
  const auto& r = options_.regions;
  if (!r.fallback_to_cluster_box || !(r.fallback_evidence_lengths > 0.0) || !(r.shift_check_ratio > 0.0) || window.empty()) {
    return window;
  }
  const int grow = static_cast<int>(std::ceil(evidence_lengthen_px()));
  return cv::Rect(window.x - grow, window.y - grow, window.width + 2 * grow, window.height + 2 * grow) &
         cv::Rect(0, 0, image_size.width, image_size.height);
}

std::vector<cv::Rect> Segmenter::required_crops(const MotionEstimate& motion, cv::Size image_size) const {
  std::vector<cv::Rect> rois;
  if (options_.method == SegmentationMethod::Clustering) return rois;
  for (const auto& c : cluster(motion, image_size, nullptr)) {
    const cv::Rect window = evidence_window_of(window_of(c, image_size), image_size);
    if (!window.empty()) rois.push_back(window);
  }
  return rois;
}

cv::Mat Segmenter::normalised_accumulator(SegmentationMethod method, const cv::Mat& gray) const {
  return normalise_accumulator(method_gradient(method).gradient(gray, options_.gradients),
                               references_[static_cast<size_t>(method)]);
}

cv::Mat Segmenter::accumulator(const cv::Mat& gray) const {
  if (method_gradient(options_.method).gradient) return normalised_accumulator(options_.method, gray);
  std::vector<cv::Mat> fused;  // fusion: the fused methods' accumulators, in list order
  for (SegmentationMethod method : kSegmentationMethods) {
    if (method_gradient(method).fused) fused.push_back(normalised_accumulator(method, gray));
  }
  return fuse_accumulators(fused, options_.regions.fusion_rule);
}

std::vector<Region> Segmenter::segment_window(const cv::Mat& gray, const cv::Rect& window,
                                              const FeatureCluster& cluster,
                                              const std::vector<cv::Point2d>& feature_positions) const {
  const auto& r = options_.regions;
  const cv::Mat acc = accumulator(gray);
  const bool summed = options_.method == SegmentationMethod::Fusion && r.fusion_rule == FusionRule::Sum;
  const double full_scale = summed ? static_cast<double>(fused_methods()) * 255.0 : 255.0;
  const double threshold = adaptive_threshold(acc, r.threshold_quantile, r.threshold_min_fraction * full_scale);
  const int connectivity = r.connectivity != 0 ? r.connectivity : method_gradient(options_.method).connectivity;

  const double vehicle_length = scene_.metres_to_px(scene_.vehicle_length_m);
  const double vehicle_width = scene_.metres_to_px(scene_.vehicle_width_m);
  SplitRule split;
  split.max_length_px = r.split_length_factor * vehicle_length;
  split.max_width_px = r.split_width_factor * vehicle_width;
  std::vector<Region> regions;
  const std::vector<Blob> blobs =
      extract_blobs(acc, threshold, r.closing_size_px, r.edge_band_px, r.box_fit, connectivity, 3, split);
  for (GroupedBlob& group : group_vehicle_parts(blobs, r.group_length_factor * vehicle_length,
                                                r.group_width_factor * vehicle_width, r.group_touch_px)) {
    group.box.cx += window.x;
    group.box.cy += window.y;
    const OrientedBox& box = group.box;
    if (box.length < r.min_length_factor * vehicle_length || box.width < r.min_width_factor * vehicle_width ||
        !within_vehicle_size(box)) {
      continue;
    }
    const int support = static_cast<int>(features_within(box, r.support_margin_px, feature_positions).size());
    if (support < r.min_supporting_features || support == 0) continue;
    Region region;
    region.box = box;
    region.method = options_.method;
    region.score = static_cast<double>(support) / static_cast<double>(feature_positions.size());
    region.cluster_id = static_cast<int32_t>(cluster.id);
    regions.push_back(region);
  }
  return regions;
}

SegmentationResult Segmenter::process(const Frame& frame, const MotionEstimate& motion) {
  return process(make_segmentation_input(frame, required_crops(motion, frame.image.size())), motion);
}

SegmentationResult Segmenter::process(const SegmentationInput& input, const MotionEstimate& motion) {
  stats_ = SegmentationStats{};
  SegmentationResult result;
  result.stream_id = motion.stream_id;
  result.frame_index = motion.frame_index;
  result.capture_time_ns = motion.capture_time_ns;
  result.clusters = cluster(motion, input.image_size, &stats_.clustering);

  if (options_.method == SegmentationMethod::Clustering) {
    for (const auto& c : result.clusters) result.regions.push_back(cluster_region(c));
    return result;
  }

  std::vector<const ImageCrop*> crops;
  for (const auto& crop : input.crops) {
    if (crop_usable(crop)) crops.push_back(&crop); else ++stats_.invalid_crops;
  }
  // Positions of the clustered features by id (ids are unique in a well-formed estimate; a
  // duplicated id contributes every position it has).
  std::multimap<uint64_t, cv::Point2d> positions;
  for (const auto& f : motion.features) {
    if (f.moving && std::isfinite(f.position.x) && std::isfinite(f.position.y)) positions.emplace(f.id, f.position);
  }

  // The shift check compares with the previous frame: only the frame right after it, and only
  // through a homography the motion layer trusted.
  const auto& r = options_.regions;
  const bool shift_check = r.shift_check_ratio > 0.0 && previous_frame_ >= 0 && previous_stream_ == motion.stream_id &&
                           previous_frame_ + 1 == motion.frame_index && motion.quality.valid && is_finite(motion.homography);
  const Homography previous_from_current = shift_check ? motion.homography.inv() : Homography::eye();
  std::vector<ImageCrop> windows;
  shadow_.reset();  // this frame's regions vote
  const double evidence_margin_px = r.motion_evidence_margin_widths * scene_.metres_to_px(scene_.vehicle_width_m);

  std::vector<Region> candidates;
  for (const auto& c : result.clusters) {
    std::vector<cv::Point2d> feature_positions;
    for (uint64_t id : c.feature_ids) {
      auto [first, last] = positions.equal_range(id);
      for (auto it = first; it != last; ++it) feature_positions.push_back(it->second);
    }
    const cv::Rect wanted = window_of(c, input.image_size);
    cv::Rect outer = evidence_window_of(wanted, input.image_size);  // holds `wanted`
    // The crop that covers the window with the evidence's margin, else the one that covers most of it.
    const ImageCrop* source = nullptr;
    int best_area = 0;
    for (const ImageCrop* crop : crops) {
      const int area = (crop->roi & outer).area();
      if (area > best_area) {
        best_area = area;
        source = crop;
      }
      if (area == outer.area()) break;
    }
    std::vector<Region> regions;
    const cv::Rect window = source != nullptr ? wanted & source->roi : cv::Rect();
    if (source != nullptr && !wanted.empty() && !window.empty()) {
      outer &= source->roi;
      cv::Mat pixels = source->pixels(outer - source->roi.tl());
      cv::Mat outer_gray;
      if (pixels.channels() == 3) cv::cvtColor(pixels, outer_gray, cv::COLOR_BGR2GRAY); else outer_gray = pixels;
      const cv::Mat gray = outer_gray(window - outer.tl());
      ++stats_.windows;
      regions = segment_window(gray, window, c, feature_positions);
      const ShiftSearch search{c.velocity, r.shift_check_search_px, r.shift_check_min_speed_px};
      const bool compared = shift_check && std::hypot(c.velocity[0], c.velocity[1]) >= r.shift_check_min_speed_px;
      // `compared` implies shift_check_ratio > 0, so `current` is there whenever it is used.
      std::optional<ImageCrop> current;
      std::vector<std::optional<ShiftErrors>> checked(regions.size());  // each kept region's shift check
      if (r.shift_check_ratio > 0.0) {
        current = ImageCrop{outer, outer_gray.data == pixels.data ? outer_gray.clone() : outer_gray};  // kept past this frame
        if (compared) {
          std::vector<Region> moving;
          checked.clear();
          for (Region& region : regions) {
            const auto e = compare_shifts(*current, region.box, search, previous_from_current, previous_windows_);
            if (e && e->moving_error >= r.shift_check_ratio * e->static_error) {
              ++stats_.static_regions;
              continue;
            }
            moving.push_back(std::move(region));
            checked.push_back(e);
          }
          regions = std::move(moving);
        }
      }
      for (size_t i = 0; i < regions.size(); ++i) {
        Region& region = regions[i];
        shadow_.observe(gray, window.tl(), region.box);  // the blob as found: its dark side is the shadow
        if (compared && evidence_margin_px > 0.0) {
          const auto e = motion_evidence(*current, region.box, evidence_margin_px, search, previous_from_current, previous_windows_);
          if (e && e->inside_fraction < r.motion_evidence_max_inside && std::abs(e->across_px) >= r.motion_evidence_min_offset_px) {
            const OrientedBox moved = moved_in_own_frame(region.box, 0.0, e->across_px);
            // Only onto something that moves more plainly than what the region held (its shift check
            // above, on the same box): on noise (an interlaced clip's static slab) the evidence's
            // centroid is noise too.
            if (moves_more_plainly(*current, moved, checked[i], search, previous_from_current, previous_windows_)) {
              region.box = moved;
              ++stats_.evidence_moves;
            }
          }
        }
        region.box = recentred_on_features(region.box, features_within(region.box, r.support_margin_px, feature_positions),
                                           r.recentre_min_offset_fraction);
      }
      if (regions.empty() && compared && r.fallback_to_cluster_box && r.fallback_evidence_lengths > 0.0 &&
          within_vehicle_size(c.box)) {
        const double margin_px = r.fallback_evidence_widths * scene_.metres_to_px(scene_.vehicle_width_m);
        if (auto placed = region_on_evidence(c, *current, search, previous_from_current, previous_windows_, margin_px,
                                             evidence_lengthen_px(), r.fallback_evidence_max_ratio, options_.method)) {
          regions.push_back(*placed);
          ++stats_.evidence_fallbacks;
        }
      }
      if (current) windows.push_back(std::move(*current));
    } else {
      ++stats_.windows_without_pixels;
    }
    if (options_.regions.fallback_to_cluster_box) {
      // A box around features is held to the sizes a blob is held to: features strung along an
      // edge longer than any vehicle are no vehicle.
      if (regions.empty()) {
        if (within_vehicle_size(c.box)) {
          ++stats_.fallback_regions;
          regions.push_back(cluster_region(c));
        }
      } else if (auto extra = uncovered_features_region(c, feature_positions, regions); extra && within_vehicle_size(extra->box)) {
        ++stats_.fallback_regions;
        regions.push_back(*extra);
      }
    }
    candidates.insert(candidates.end(), regions.begin(), regions.end());
  }

  for (const Region& candidate : candidates) {
    const bool duplicate = std::any_of(result.regions.begin(), result.regions.end(), [&](const Region& kept) {
      return covered_fraction(candidate.box, kept.box) > options_.regions.duplicate_overlap;
    });
    if (duplicate) ++stats_.duplicate_regions; else result.regions.push_back(candidate);
  }
  // Gradient blobs hold the vehicle's shadow; boxes made from the features (method=clustering) are left.
  if (const auto shadow = shadow_.offset(); shadow && r.shadow_correction_factor > 0.0) {
    stats_.shadow_offset_px = *shadow;
    for (Region& region : result.regions) {
      if (region.method == SegmentationMethod::Clustering) continue;
      region.box.cx -= r.shadow_correction_factor * (*shadow)[0];
      region.box.cy -= r.shadow_correction_factor * (*shadow)[1];
      if (r.shadow_size_correction_factor > 0.0) {
        region.box = shrunk_by_shadow(region.box, r.shadow_size_correction_factor * *shadow);
      }
    }
  }
  previous_stream_ = motion.stream_id;
  previous_frame_ = motion.frame_index;
  previous_windows_ = std::move(windows);
  return result;
}

}  // namespace uavmot::segmentation
