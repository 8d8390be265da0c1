#pragma once
// Every parameter of the multi-object tracking layer (paper section IV), with defaults.
// Where the paper gives a value (20 features per track, "small" gating threshold,
// "a few" coasting frames) the default follows it; the rest are documented in docs/tracking.md.

#include <string>

#include "uavmot/core/scene_info.hpp"
#include "uavmot/core/yaml_config.hpp"

namespace uavmot::tracking {

struct TrackerOptions {
  // --- Which regions are measurements -------------------------------------------------------
  // "auto": Fusion regions when the frame has any, otherwise every region;
  // "all": every region; or one method name (clustering, korn, morphological, lbp, fusion).
  std::string region_method = "auto";

  // --- Kalman filter (kalman_model, motion_model, updater) ---------------------------------
  // The motion model (predictor) by name: "homography_cv", constant ground velocity with the
  // homography as control input (the paper). The list is in src/motion_model.cpp.
  std::string motion_model = "homography_cv";
  double process_accel_sigma_px = 0.08;     // white-noise acceleration, px/frame^2
  double process_size_sigma_px = 0.05;      // random walk of width and length, px/frame
  double process_angle_sigma_deg = 1.0;     // random walk of the axis angle, deg/frame
  double region_position_sigma_px = 1.0;    // region centre measurement noise
  double region_size_sigma_px = 1.5;        // region width/length measurement noise
  double region_angle_sigma_deg = 5.0;      // region angle measurement noise
  double min_elongation_for_angle = 1.25;   // length/width below which a region's angle is ~unknown
  double ambiguous_angle_sigma_deg = 45.0;  // angle noise used for such near-square regions
  double reconstruction_sigma_px = 1.0;     // centre reconstructed from features (merge handling)
  double init_velocity_sigma = 3.0;         // px/frame, new track without moving features
  double init_velocity_sigma_features = 0.5;  // px/frame, new track started from its features' motion
  double min_box_size_px = 1.0;             // width/length never shrink below this

  // --- Region-to-track assignment (region_associator) --------------------------------------
  // A region validates a prediction when their intersection exceeds this fraction of the smaller box
  // (paper: "chosen small for high tolerance during validation gating").
  double min_intersection_fraction = 0.05;

  // --- Feature-to-track assignment (feature_associator) ------------------------------------
  int max_features_per_track = 20;          // paper IV-B
  double feature_motion_abs_tolerance = 0.5;  // px/frame: |v_feature - v_track| allowed ...
  double feature_motion_rel_tolerance = 0.3;  // ... or this fraction of |v_track|, whichever is larger
  double feature_direction_tolerance_deg = 30.0;  // direction check when the track moves faster than:
  double feature_min_speed_for_direction = 0.5;   // px/frame
  double feature_position_margin = 0.25;    // a linked feature may leave the predicted box by this fraction
  double feature_reconstruction_outlier_px = 2.5;  // linked feature whose centre estimate is this far from the median
  double feature_uv_smoothing = 0.2;        // how fast a feature's stored box position follows unambiguous updates
  int min_reconstruction_features = 2;      // features needed to reconstruct a measurement
  // A linked feature that stops moving (its vehicle slows to a halt) still supports the track once
  // the link is this many region-updated frames old; 0: links end when their feature stops.
  int stopped_link_min_frames = 10;
  // ... and only on a track whose anchor is this many x SceneInfo's vehicle length from where it
  // started: a car that drove and halted, not a parked car whose corner a passing car dragged along
  // for a few frames (held through its "stop" for 110 frames on paper seed 103). 0.6 cost less
  // correct rate than 1.0 on the tuning seeds for the same false alarms. 0: no such check.
  double stopped_link_min_travel_lengths = 0.6;
  // The linked features' median velocity is a direct measurement of the track's ground velocity
  // (a region only gives positions, whose differences are noisy); 0 disables.
  double feature_velocity_sigma_px = 0.1;   // px/frame, 1-sigma per axis
  // A vehicle drives along its length: above this speed (px/frame) the direction of the linked
  // features' median velocity measures the box's axis angle with this 1-sigma; 0 disables.
  double heading_min_speed_px = 0.3;
  double heading_sigma_deg = 10.0;
  // A track without a feature heading (a small or slow car has one feature, or none fast enough) that
  // has travelled this many x SceneInfo's vehicle length from where it started takes the direction of
  // that travel as its heading, unless its velocity points more than travel_heading_max_turn_deg away
  // (it has turned since). 0 disables each.
  double travel_heading_min_lengths = 0.5;
  double travel_heading_max_turn_deg = 45.0;
  // The travel is the most recent this many x the vehicle length: the point it is measured from
  // trails the track on a leash of that length, so after a bend the heading turns with the road
  // (a chord from the first region would point across it for ever). 0: from the first region.
  double travel_heading_max_lengths = 2.0;
  // With a known heading, a region is lengthened to reach this far (px) beyond the linked features'
  // ends, up to SceneInfo's vehicle length: a road-grey car's blob may be its windscreen alone, while
  // its features sit on both window bars. Negative disables.
  double feature_span_margin_px = 2.0;
  // Criteria (2) and (3) look for new features of a track under way in its prediction lengthened to
  // this many x SceneInfo's vehicle length, so a blob of one part of a car still links the rest.
  // 0 keeps the prediction as it is (the paper).
  double link_min_length_factor = 1.3;

  // --- Split and merge handling (split_merge) ----------------------------------------------
  // Regions inside one track's gate are fragments of one object when their motion agrees within the
  // feature motion tolerances and their union fits in the predicted box enlarged by this factor.
  double fragment_union_factor = 1.4;
  // A region shared by several tracks but no larger than SceneInfo's vehicle size times this factor
  // holds one object tracked in pieces: the senior track keeps it, the others are absorbed. 0 disables.
  double single_object_size_factor = 1.5;
  // The largest object the tracker assembles from fragments or pieces: this wide (a truck and the
  // blur of its outline) and this many x SceneInfo's vehicle length (the segmentation's longest
  // region; a 10.5 m truck's cab and trailer boxes overstate it, together 14 m).
  double max_object_width_m = 4.0;
  double max_object_length_factor = 3.3;
  // A track's own region wider than this (read along the track's axis) is more than one vehicle: a
  // truck and an untracked car beside it in one blob, or a blob lying across two lanes. The track
  // takes only its own lane of it: the region read along the track's axis, cut across to the
  // track's predicted width. 0 disables.
  double max_region_width_m = 4.0;
  // Two tracks driving nose to tail are pieces of one long vehicle (truck cab and trailer) when the
  // features on both move at piece_min_speed_mps or faster with velocities within
  // piece_max_speed_difference_mps (along the line between them; across it, plus the turn rate
  // below), one is behind the other along the direction of travel (centres
  // at most piece_max_lateral_m apart across it), the gap between their boxes is at most
  // piece_max_gap_m, and each and both together fit the largest object above (piece_merger.hpp).
  // piece_max_gap_m = 0 disables. 2 m: a truck's uniform trailer roof leaves the segmentation blobs
  // at its ends up to 1.9 m apart (docs/tracking.md, step 6).
  double piece_max_gap_m = 2.0;
  double piece_min_speed_mps = 1.0;
  double piece_max_speed_difference_mps = 1.0;
  // ... across the line between the pieces, plus this turn rate x their distance: a truck in a bend
  // turns as one body, so its ends' velocities differ across it (16 deg/s on `paper` seed 106).
  double piece_max_turn_rate_dps = 20.0;
  double piece_max_lateral_m = 0.9;

  // --- Initiation (initiator) ---------------------------------------------------------------
  // A free region is not started as a new track while this fraction of it lies inside a live track.
  double init_max_overlap_fraction = 0.3;
  double min_region_area_px = 4.0;          // smaller regions are ignored

  // --- Lifecycle (deleter) ------------------------------------------------------------------
  int confirm_hits = 3;                     // region hits ...
  int confirm_window = 5;                   // ... within this many frames confirm a tentative track
  // Fewer hits suffice when the track already has this many linked moving features that move like
  // it (clutter has none); 0 disables.
  int confirm_hits_with_features = 2;
  int confirm_min_features = 2;
  // ... and fewer linked features, this many, where the ground under the box came into view at most
  // quick_confirm_max_ground_frames ago, the camera's motion carried back: a vehicle the camera has
  // just uncovered has had no time for a second feature, and under a fast camera it is in view for
  // few frames. Elsewhere one feature more is worth the wait: everywhere, and in the tracker's
  // first frames, it raised false alarms (docs/tracking.md). < 0 = never.
  int quick_confirm_min_features = 1;
  int quick_confirm_max_ground_frames = 8;
  // A tentative track confirms only once its estimated ground speed reaches this: roofs, trees and
  // parked cars whose features jitter make regions too, but they do not go anywhere. Once confirmed
  // a track may stop (stop-and-go). 0 disables.
  double confirm_min_speed_mps = 1.0;
  // A tentative track does not confirm while its box comes within this distance (px) of the image
  // border. There the camera's motion uncovers or hides part of a static object, so its region
  // grows or shrinks and the box centre moves; its features at the uncovered edge move too: the
  // look of motion (real clips: most false tracks were there). 0 = only a box reaching outside the
  // image waits.
  double confirm_border_margin_px = 1.0;
  // ... unless its ground velocity points into the image, within this angle of the inward normal at
  // every side it reaches, and it has this many linked moving features: a vehicle driving into the
  // view. A static object the camera uncovers grows outward over the ground instead. 0 = never.
  double confirm_entering_max_angle_deg = 60.0;
  int confirm_entering_min_features = 1;
  int tentative_max_misses = 1;             // a tentative track missing more frames in a row is deleted
  int max_coast_frames = 5;                 // a confirmed track coasts this many frames on prediction
  // An established track (at least gap_min_hits region hits) that misses up to this many frames in a
  // row is still reported as confirmed: one missing region is a segmentation gap, not a lost object.
  int gap_frames = 2;
  int gap_min_hits = 15;
  // Then it waits hidden (dormant) at its last measured ground position for this many frames and is
  // re-acquired with the same id by a new region nearby (stop-and-go); 0 deletes it at once.
  int reacquire_max_frames = 375;           // 15 s at 25 fps: longer than a red light
  double reacquire_radius_m = 3.0;          // along the track's axis; converted to px with SceneInfo::gsd_m
  double reacquire_lateral_m = 1.0;         // across the track's axis (a car in the next lane is not it)
  double reacquire_size_ratio = 1.6;        // max ratio between the region's and the track's length/width

  // --- The image (0 = unknown) ----------------------------------------------------------------
  // A track whose centre leaves the image stops being reported at once: a confirmed one goes dormant
  // (re-acquirable if the view comes back), a tentative one is deleted. The size comes with each
  // motion estimate (MotionEstimate::image_width/height); these are used only for input that
  // carries none.
  int image_width = 0;
  int image_height = 0;
};

// Reads the `tracking:` section; every key optional, unknown keys and out-of-range values are
// uavmot::InputError naming the file, line and key.
TrackerOptions load_tracker_options(const ConfigNode& node);

// Throws uavmot::InvalidArgument when a value is outside its documented range.
void validate(const TrackerOptions& options);

}  // namespace uavmot::tracking
