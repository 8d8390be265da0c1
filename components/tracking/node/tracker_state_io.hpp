#pragma once
// The tracker's state on the wire (uavmot/tracker_state) and on disk: a restarted tracking
// component restores it and continues with the same track ids. A file, because transient-local
// data dies with the writer that held it: the killed process cannot hand its last state to the
// one that replaces it; the file survives the crash (written by rename, so never half-written).

#include <optional>
#include <string>

#include "tracker_state.h"
#include "uavmot/tracking/tracker_state.hpp"

namespace uavmot::tracking {

msg::TrackerSnapshot to_msg(const TrackerState& state, const std::string& stream_id, int64_t frame_index);
// nullopt (with `why`) for a snapshot that is malformed; Tracker::restore checks consistency.
std::optional<TrackerState> from_msg(const msg::TrackerSnapshot& snapshot, std::string& why);

// Writes the snapshot to `path` atomically and durably (uavmot::write_file_durably): "UTRKSTAT",
// a u32 format version (little-endian), then the snapshot's CDR. Throws OutputError naming the
// file and the reason.
void save_snapshot(const msg::TrackerSnapshot& snapshot, const std::string& path);
// nullopt when the file does not exist; throws InputError when it exists but cannot be decoded, or
// is of another format version (an earlier uavmot's file had no mark: its CDR would be misread).
std::optional<msg::TrackerSnapshot> load_snapshot(const std::string& path);

}  // namespace uavmot::tracking
