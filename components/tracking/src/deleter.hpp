#pragma once
// Track lifecycle (paper IV-D): a track is tentative until it has `confirm_hits` region updates within
// `confirm_window` frames; a confirmed track without region or feature support coasts on its
// prediction for `max_coast_frames`, then waits hidden (dormant) at its last measured ground position
// for `reacquire_max_frames` to be re-acquired, then is deleted. Tentative tracks that miss more than
// `tentative_max_misses` frames in a row, or fail to confirm in time, are deleted at once. An
// established track (`gap_min_hits`) missing up to `gap_frames` in a row is still reported confirmed.

#include <opencv2/core/types.hpp>

#include "uavmot/core/homography.hpp"
#include "uavmot/tracking/tracker_options.hpp"
#include "uavmot/tracking/tracker_state.hpp"

namespace uavmot::tracking {

enum class Fate { Keep, Dormant, Delete };

// False when the image size is known (both sides positive) and the box centre lies outside the image.
bool inside_view(const OrientedBox& box, const cv::Size& image);

// True unless the image size is known and a corner of the box lies outside the image.
bool wholly_inside_view(const OrientedBox& box, const cv::Size& image);

// True unless the image size is known and a corner of the box lies within `margin_px` (>= 0) of the
// image's edge or outside it.
bool clear_of_border(const OrientedBox& box, const cv::Size& image, double margin_px);

// True when the box's ground velocity points into the image, within `max_angle_deg` of the inward
// normal, at every side of the image that a corner of the box comes within `margin_px` of: a vehicle
// driving into the view. A static object that the camera uncovers grows outward instead (its centre
// moves toward the border over the ground). False when the image size is unknown, the velocity is
// zero or `max_angle_deg` is not positive.
bool entering_view(const OrientedBox& box, const cv::Point2d& velocity, const cv::Size& image, double margin_px,
                   double max_angle_deg);

// Whether a tentative track whose box is `box` may confirm in this frame: clear of the image border
// (TrackerOptions::confirm_border_margin_px), or driving into the view (entering_view with
// TrackerOptions::confirm_entering_max_angle_deg, the track's velocity) with at least
// TrackerOptions::confirm_entering_min_features linked moving features.
bool may_confirm_at(const TrackRecord& track, const OrientedBox& box, const cv::Size& image, const TrackerOptions& options);

// Records one frame in the track's history: a region hit, support by features only, or nothing.
// An established track that misses a frame stays confirmed for `gap_frames` when `may_bridge_gap`
// (the caller passes false at the image border, where a vehicle misses its regions because it leaves).
// A tentative track is confirmed only when its estimated speed is at least `confirm_min_speed_px`
// (px/frame; the tracker converts TrackerOptions::confirm_min_speed_mps with the scene's GSD and fps)
// and only when `may_confirm` (the caller passes false while the box touches the image border,
// where a static object that the camera uncovers looks like motion). `new_ground`: the box is on ground
// that has just come into view (TrackerOptions::quick_confirm_max_ground_frames), where fewer linked
// features confirm.
void record_frame(TrackRecord& track, bool region_hit, bool supported, const TrackerOptions& options,
                  bool may_bridge_gap = true, double confirm_min_speed_px = 0.0, bool may_confirm = true,
                  bool new_ground = false);

// What happens to a live track after record_frame().
// `in_view`: see inside_view(); a track that left the view goes dormant (confirmed) or is deleted.
Fate decide_fate(const TrackRecord& track, bool in_view, const TrackerOptions& options);

// Carries dormant tracks' anchors through the frame's homography and deletes the expired ones.
void age_dormant(TrackerState& state, const Homography& h, const TrackerOptions& options);

}  // namespace uavmot::tracking
