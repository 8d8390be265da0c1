#pragma once
// Step 5 of a frame for one track: the Kalman update with what split/merge handling measured, and
// the commit of the posterior into the track's record.

#include "feature_associator.hpp"
#include "track_in_frame.hpp"
#include "uavmot/tracking/tracker_options.hpp"

namespace uavmot::tracking {

// First the linked features' own motion (velocity, and above heading_min_speed_px the heading);
// without a feature heading, a region-measured track that has travelled far enough takes the
// direction of its travel as heading. Then the region, read along that heading and lengthened to
// the features (at most `vehicle_length_px`), or a reconstructed centre; a track with neither but
// enough linked features is carried by them. Sets region_hit and supported.
void update_track(TrackInFrame& track, const FeatureIndex& features, const TrackerOptions& options,
                  double vehicle_length_px);

// The posterior becomes the record's state and box; a measured track's anchor follows it, and after
// a region update the stored feature positions follow the box by `uv_smoothing`.
void commit_update(TrackInFrame& track, const FeatureIndex& features, double uv_smoothing);

}  // namespace uavmot::tracking
