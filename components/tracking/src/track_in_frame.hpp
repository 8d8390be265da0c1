#pragma once
// One track during one frame: its persistent record (what TrackerState keeps between frames) and
// what the stages work out for it in this frame. Tracker::process keeps one of these per live track,
// so the stages pass one vector instead of a vector per quantity.

#include <utility>

#include <opencv2/core/types.hpp>

#include "kalman_model.hpp"
#include "uavmot/tracking/tracker_state.hpp"

namespace uavmot::tracking {

enum class MeasurementKind { None, Box, Centre };

// What split and merge handling gives a track to update with.
struct TrackMeasurement {
  MeasurementKind kind = MeasurementKind::None;
  OrientedBox box;         // kind == Box
  cv::Point2d centre;      // kind == Centre
  bool merged = false;     // in a merge this frame: its features must not be relearnt from this box
  bool size_jump = false;  // split off other regions or absorbed pieces: its size may change abruptly
};

struct TrackInFrame {
  TrackRecord record;

  // Prediction (motion model).
  KalmanState kalman;         // the prior, then (after the update) the posterior
  OrientedBox predicted;      // box of the prior
  cv::Vec2d velocity;         // velocity of the prior, px/frame
  bool velocity_known = false;  // two region hits: the velocity was observed, not guessed

  // Association and split/merge handling.
  TrackMeasurement measurement;
  bool absorbed = false;  // a piece of another track's object: deleted at the end of the frame

  // Update.
  bool region_hit = false;  // updated with a region (box)
  bool supported = false;   // updated with a centre from its features, no region
  OrientedBox posterior;    // box of the posterior, once committed
};

// A track's velocity is observed once it has two region hits; before that it is a guess.
inline bool velocity_observed(const TrackRecord& record) { return record.hits >= 2; }

// A track predicted to this frame: the prior and what follows from it.
inline TrackInFrame predicted_track(TrackRecord record, const KalmanState& prior) {
  TrackInFrame t;
  t.velocity_known = velocity_observed(record);
  t.record = std::move(record);
  t.kalman = prior;
  t.predicted = box_of(prior.mean);
  t.velocity = velocity_of(prior.mean);
  return t;
}

}  // namespace uavmot::tracking
