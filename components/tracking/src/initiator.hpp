#pragma once
// Track initiation (paper IV-A): regions that validate no track (or that split handling left over)
// start tentative tracks, unless they mostly lie inside a live track, or are a blob less than half a
// vehicle right at the nose or tail of a confirmed moving track (its cab or windscreen, by the piece
// rule of piece_merger.hpp with twice the gap). A region near a dormant track's
// last measured ground position, of similar size, re-acquires that track with its old id (stop-and-go).
// Features never start tracks (paper IV-B).

#include <vector>

#include "uavmot/core/scene_info.hpp"
#include "frame_input.hpp"
#include "uavmot/tracking/tracker_options.hpp"
#include "uavmot/tracking/tracker_state.hpp"

namespace uavmot::tracking {

// Starts or re-acquires tracks for `free_regions` (indices into input.regions) and appends them to
// state.tracks; `live_boxes` are the current boxes of the tracks already in state.tracks.
void initiate_tracks(const std::vector<int>& free_regions, const FrameInput& input,
                     const std::vector<OrientedBox>& live_boxes, const TrackerOptions& options, const SceneInfo& scene,
                     TrackerState& state);

}  // namespace uavmot::tracking
