#include "deleter.hpp"

#include <algorithm>
#include <bit>
#include <cmath>

#include "kalman_model.hpp"
#include "record_places.hpp"
#include "uavmot/core/image_bounds.hpp"

namespace uavmot::tracking {

void record_frame(TrackRecord& track, bool region_hit, bool supported, const TrackerOptions& options,
                  bool may_bridge_gap, double confirm_min_speed_px, bool may_confirm, bool new_ground) {
  ++track.age;
  const uint32_t window_mask = options.confirm_window >= 32 ? 0xffffffffu : ((1u << options.confirm_window) - 1u);
  track.hit_history = ((track.hit_history << 1) | (region_hit ? 1u : 0u)) & window_mask;
  if (region_hit) ++track.hits;
  track.frames_since_update = (region_hit || supported) ? 0 : track.frames_since_update + 1;
  if (track.state == TrackState::Tentative) {
    const int hits = std::popcount(track.hit_history);
    const bool by_features = options.confirm_hits_with_features > 0 && hits >= options.confirm_hits_with_features &&
                             static_cast<int>(track.features.size()) >=
                                 (new_ground ? options.quick_confirm_min_features : options.confirm_min_features);
    const bool goes_somewhere = std::hypot(track.mean[kVx], track.mean[kVy]) >= confirm_min_speed_px;
    // At the border neither region hits nor linked features prove motion (see
    // TrackerOptions::confirm_border_margin_px): the track waits until it is inside.
    if ((hits >= options.confirm_hits || by_features) && goes_somewhere && may_confirm) track.state = TrackState::Confirmed;
    return;
  }
  const bool bridged = may_bridge_gap && static_cast<int>(track.frames_since_update) <= options.gap_frames &&
                       static_cast<int>(track.hits) >= options.gap_min_hits;
  track.state = (track.frames_since_update == 0 || bridged) ? TrackState::Confirmed : TrackState::Coasting;
}

namespace {

bool image_size_known(const cv::Size& image) { return image.width > 0 && image.height > 0; }

// The image's sides that the box comes within `margin_px` (>= 0) of, or reaches past. The image
// covers [-0.5, width - 0.5) x [-0.5, height - 0.5) (image_bounds.hpp).
struct SidesReached {
  bool left = false, right = false, top = false, bottom = false;
  bool any() const { return left || right || top || bottom; }
};

SidesReached sides_reached(const OrientedBox& box, const cv::Size& image, double margin_px) {
  const cv::Rect2d b = axis_aligned_bounds(box);
  return {b.x - margin_px < -0.5, b.x + b.width + margin_px >= image.width - 0.5, b.y - margin_px < -0.5,
          b.y + b.height + margin_px >= image.height - 0.5};
}

}  // namespace

bool inside_view(const OrientedBox& box, const cv::Size& image) {
  return !image_size_known(image) || inside_image({box.cx, box.cy}, image);
}

bool wholly_inside_view(const OrientedBox& box, const cv::Size& image) {
  if (!image_size_known(image)) return true;
  for (const auto& c : box_corners(box)) {
    if (!inside_image(c, image)) return false;
  }
  return true;
}

bool clear_of_border(const OrientedBox& box, const cv::Size& image, double margin_px) {
  return !image_size_known(image) || !sides_reached(box, image, margin_px).any();
}

bool entering_view(const OrientedBox& box, const cv::Point2d& velocity, const cv::Size& image, double margin_px,
                   double max_angle_deg) {
  const double speed = std::hypot(velocity.x, velocity.y);
  if (!image_size_known(image) || max_angle_deg <= 0.0 || speed <= 0.0) return false;
  const double min_cos = std::cos(max_angle_deg * M_PI / 180.0);
  // Every side the box reaches (the sides clear_of_border tests) must be one it comes in through.
  const auto inward = [&](double along_normal) { return along_normal >= min_cos * speed; };
  const SidesReached sides = sides_reached(box, image, margin_px);
  return (!sides.left || inward(velocity.x)) && (!sides.right || inward(-velocity.x)) &&
         (!sides.top || inward(velocity.y)) && (!sides.bottom || inward(-velocity.y));
}

bool may_confirm_at(const TrackRecord& track, const OrientedBox& box, const cv::Size& image, const TrackerOptions& options) {
  const double margin = options.confirm_border_margin_px;
  if (clear_of_border(box, image, margin)) return true;
  return static_cast<int>(track.features.size()) >= options.confirm_entering_min_features &&
         entering_view(box, {track.mean[kVx], track.mean[kVy]}, image, margin, options.confirm_entering_max_angle_deg);
}

Fate decide_fate(const TrackRecord& track, bool in_view, const TrackerOptions& options) {
  if (!in_view) {
    return (track.state != TrackState::Tentative && options.reacquire_max_frames > 0) ? Fate::Dormant : Fate::Delete;
  }
  if (track.state == TrackState::Tentative) {
    const bool missed_too_often = static_cast<int>(track.frames_since_update) > options.tentative_max_misses;
    const bool too_late = static_cast<int>(track.age) >= options.confirm_window;
    return (missed_too_often || too_late) ? Fate::Delete : Fate::Keep;
  }
  if (static_cast<int>(track.frames_since_update) <= options.max_coast_frames) return Fate::Keep;
  return options.reacquire_max_frames > 0 ? Fate::Dormant : Fate::Delete;
}

void age_dormant(TrackerState& state, const Homography& h, const TrackerOptions& options) {
  for (auto& track : state.dormant) {
    carry_places(track, h);
    ++track.frames_dormant;
  }
  std::erase_if(state.dormant, [&](const TrackRecord& t) {
    return static_cast<int>(t.frames_dormant) > options.reacquire_max_frames || !uavmot::is_finite(t.anchor_box);
  });
}

}  // namespace uavmot::tracking
