#pragma once
// Predictions from a recording of the chain (uavmot record): the tracks recorded on uavmot/tracks
// and, when recorded, the homographies and features on uavmot/motion, of one stream.

#include <string>

#include "uavmot/eval/predictions.hpp"

namespace uavmot::eval {

// `stream_id` empty: the recording's only stream (InputError naming them when there are several).
// Throws InputError when the file is not MCAP, has no uavmot/tracks, is damaged before any track
// list, or holds a frame outside 1..info.length.
Predictions load_recorded_predictions(const std::string& path, const std::string& stream_id, const SequenceInfo& info);

}  // namespace uavmot::eval
