#pragma once
// MISB ST 0601 UAS Datalink Local Set: 16-byte universal key, BER length, then items of BER-OID
// tag, BER length and value, ending with the checksum (tag 1). Values use the standard's linear
// integer mappings, e.g. tag 13 int32 -> [-90, 90] deg as v * 180 / (2^32 - 2), with 0x80000000
// reserved as "error" (read as missing).

#include <array>
#include <cstdint>

#include "uavmot/geo/uas_metadata.hpp"

namespace uavmot::geo {

inline constexpr std::array<std::uint8_t, 16> kSt0601Key = {0x06, 0x0E, 0x2B, 0x34, 0x02, 0x0B, 0x01, 0x01,
                                                            0x0E, 0x01, 0x03, 0x01, 0x01, 0x00, 0x00, 0x00};

// The ST 0601 checksum: a 16-bit running sum of every byte from the first byte of the key up to
// and including the checksum item's tag and length, bytes at even offsets in the high byte.
std::uint16_t st0601_checksum(Bytes bytes);

// Decodes one ST 0601 packet (key, BER length, local set). A checksum that does not match is
// reported in checksum_ok, not thrown. Throws InputError when the key is not ST 0601's, the
// length runs past the end, or an item is cut short.
UasMetadata decode_st0601(Bytes packet);

}  // namespace uavmot::geo
