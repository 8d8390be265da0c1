#pragma once
// Pieces of one long vehicle (paper IV-C: "split regions of one object ... have similar motion and,
// thus, are merged and assigned to one track"). A truck's cab and trailer often carry their own
// moving features and blobs, so they start two tracks that then drive nose to tail forever. Two
// tracks measured by their own regions in this frame are pieces of one object when
//  - the features on them move at `piece_min_speed_mps` or faster (queues crawl bumper to bumper),
//    as parts of one body: velocities within `piece_max_speed_difference_mps` along the line between
//    them (a car closing in is faster), and across it within that plus what a body turning at
//    `piece_max_turn_rate_dps` gives two points that far apart (a truck's ends in a bend);
//  - one is behind the other along the direction of travel, centres at most `piece_max_lateral_m`
//    apart across it (the boxes' own angles are noise for a near-square cab);
//  - each box is at most `max_object_width_m` wide (not a box over two cars side by side);
//  - the gap between the boxes is at most `piece_max_gap_m` (a car keeps metres at speed, a
//    trailer none), and together they are at most `max_object_length_factor` vehicle lengths.
// The senior track takes the box around both as its measurement; the junior one is absorbed.

#include <vector>

#include "uavmot/core/scene_info.hpp"
#include "feature_associator.hpp"
#include "kalman_model.hpp"
#include "track_in_frame.hpp"
#include "uavmot/tracking/tracker_options.hpp"
#include "uavmot/tracking/tracker_state.hpp"

namespace uavmot::tracking {

// True when the motions of `a` and `b` (px/frame) are those of two points of one rigid body.
bool pieces_move_as_one_body(const OrientedBox& a, const cv::Vec2d& motion_a, const OrientedBox& b,
                             const cv::Vec2d& motion_b, const TrackerOptions& options, const SceneInfo& scene);

// True when `a` and `b` (posterior boxes, with the ground motion of the features on each, px/frame)
// are two pieces of one object.
bool are_pieces_of_one_object(const OrientedBox& a, const cv::Vec2d& motion_a, const OrientedBox& b,
                              const cv::Vec2d& motion_b, const TrackerOptions& options, const SceneInfo& scene);

// Merges pieces among the tracks with a region hit in this frame whose posterior box (track.kalman)
// holds moving features: the keeper's posterior is updated with the box around both, the other is
// marked absorbed. Each track takes part in at most one merge per frame, pairs in index order.
void merge_track_pieces(std::vector<TrackInFrame>& tracks, const FeatureIndex& features, const TrackerOptions& options,
                        const SceneInfo& scene);

}  // namespace uavmot::tracking
