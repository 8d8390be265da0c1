#pragma once
// The motion estimator's saved state on disk (MotionEstimator::save_state bytes): a respawned motion
// component restores it and continues bit-identically. A file, like the tracker's state
// (components/tracking/node/tracker_state_io.hpp), because the killed process cannot hand its state on.
// The node writes it with uavmot::write_file_durably (uavmot/core/durable_file.hpp).

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace uavmot::motion {

// nullopt when the file does not exist; throws InputError when it exists but cannot be read.
std::optional<std::vector<uint8_t>> load_state_file(const std::string& path);

}  // namespace uavmot::motion
