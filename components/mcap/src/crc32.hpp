#pragma once
// CRC-32 (ISO-HDLC, as zlib and the MCAP spec use), incremental.

#include <cstddef>
#include <cstdint>

namespace uavmot::mcap::detail {

// crc32_update(0, a) then crc32_update(that, b) equals the CRC of a followed by b.
uint32_t crc32_update(uint32_t crc, const void* data, size_t size);

}  // namespace uavmot::mcap::detail
