#pragma once
// The complete state of a Tracker as plain data, so it can be saved and restored across restarts:
// restoring a state and continuing gives the same tracks, bit for bit, as never having stopped.

#include <array>
#include <cstdint>
#include <vector>

#include <opencv2/core/types.hpp>

#include "uavmot/core/chain_types.hpp"
#include "uavmot/core/oriented_box.hpp"

namespace uavmot::tracking {

// Kalman state layout: centre x, y (px), ground velocity vx, vy (px/frame, current frame),
// width, length (px), axis angle (deg, (-90, 90]).
inline constexpr int kStateSize = 7;

// A local feature that supports a track (paper IV-B): where it sits on the object's box.
struct FeatureLink {
  uint64_t feature_id = 0;
  cv::Point2d box_uv;  // to_box_coordinates(track box, feature position)
  uint32_t frames_linked = 0;
};

struct TrackRecord {
  uint64_t id = 0;
  TrackState state = TrackState::Tentative;
  std::array<double, kStateSize> mean{};
  std::array<double, kStateSize * kStateSize> covariance{};  // row-major
  uint32_t age = 0;                  // frames since the track started
  uint32_t hits = 0;                 // frames with a region measurement
  uint32_t hit_history = 0;          // bit i set: region measurement i frames ago
  uint32_t frames_since_update = 0;  // frames without region or feature support
  uint32_t frames_dormant = 0;       // frames spent hidden, waiting to be re-acquired
  OrientedBox anchor_box;            // last measured box (region or features), carried by the homographies
  // The centre of the track's first region, carried by the homographies like anchor_box: how far the
  // object has gone since (a parked car that moved for a moment has not gone a car length).
  cv::Point2d origin;
  // Where the track's recent travel is measured from: the origin, pulled after the track so it stays
  // at most TrackerOptions::travel_heading_max_lengths behind (its heading after a bend).
  cv::Point2d travel_from;
  std::vector<FeatureLink> features;
};

struct TrackerState {
  uint64_t next_id = 1;
  int64_t frames_processed = 0;
  uint64_t rejected_homographies = 0;  // non-finite or degenerate: identity used instead
  uint64_t rejected_regions = 0;       // non-finite or degenerate boxes
  uint64_t rejected_features = 0;      // non-finite positions or velocities
  std::vector<TrackRecord> tracks;     // tentative, confirmed and coasting, ascending id
  std::vector<TrackRecord> dormant;    // waiting for re-acquisition, ascending id
};

}  // namespace uavmot::tracking
