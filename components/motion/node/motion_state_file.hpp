#pragma once
// The motion estimator's saved state on disk (MotionEstimator::save_state bytes): a respawned motion
// component restores it and continues bit-identically. A file, like the tracker's state
// (components/tracking/node/tracker_state_io.hpp), because the killed process cannot hand its state on.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace uavmot::motion {

// Writes `bytes` to `path` atomically and durably (temporary file, fdatasync, rename, fsync of the
// folder). Returns false on I/O errors.
bool save_state_file(const std::vector<uint8_t>& bytes, const std::string& path);
// nullopt when the file does not exist; throws InputError when it exists but cannot be read.
std::optional<std::vector<uint8_t>> load_state_file(const std::string& path);

}  // namespace uavmot::motion
