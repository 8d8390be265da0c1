#pragma once
// Foxglove schema messages as CDR payloads (XCDR1 little endian, as MCAP "cdr" channels and the
// Foxglove WebSocket protocol carry them), through the one CDR encoder (uavmot/mcap/cdr.hpp).

#include <cstdint>
#include <vector>

#include "uavmot/foxglove/messages.hpp"

namespace uavmot::foxglove {

std::vector<uint8_t> encode(const ImageAnnotations& message);
std::vector<uint8_t> encode(const CompressedImage& message);
std::vector<uint8_t> encode(const RawImage& message);

}  // namespace uavmot::foxglove
