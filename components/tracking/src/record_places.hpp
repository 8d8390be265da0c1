#pragma once
// A track's remembered places in the image: its last measured box, where it started and where its
// recent travel starts. Each frame's homography carries all of them into the next frame, whether the
// track is live or dormant.

#include "uavmot/core/homography.hpp"
#include "uavmot/tracking/tracker_state.hpp"

namespace uavmot::tracking {

void carry_places(TrackRecord& record, const Homography& h);

}  // namespace uavmot::tracking
