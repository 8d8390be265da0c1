#pragma once
// `uavmot replay --info`: what a recording holds, in the shape of `ros2 bag info`.

#include <string>

#include "uavmot/mcap/reader.hpp"

namespace uavmot::replay {

// Files, size, duration, start/end, message count, compression, one line per topic with its
// type, count and serialization format, and the damage when the file is damaged.
std::string recording_info(const mcap::Reader& reader);

// "2026-11-22 07:15:30.123456789 UTC (1795332930.123456789)"
std::string format_time(uint64_t ns);

}  // namespace uavmot::replay
