#pragma once
// MISB EG 0104 Predator UAV Basic Universal Metadata Set: a 16-byte key, BER length, then
// elements each with their own 16-byte SMPTE RP 210 key and IEEE-754 big-endian float or double
// values (no integer mappings, no checksum). Superseded by ST 0601 but still in archived video,
// e.g. Kitware's aphill_short.ts. Element keys are matched ignoring their version byte (byte 8).

#include <array>
#include <cstdint>

#include "uavmot/geo/uas_metadata.hpp"

namespace uavmot::geo {

inline constexpr std::array<std::uint8_t, 16> kEg0104Key = {0x06, 0x0E, 0x2B, 0x34, 0x02, 0x01, 0x01, 0x01,
                                                            0x0E, 0x01, 0x01, 0x02, 0x01, 0x01, 0x00, 0x00};

// Throws InputError when the key is not EG 0104's, or a length runs past the end.
UasMetadata decode_eg0104(Bytes packet);

}  // namespace uavmot::geo
