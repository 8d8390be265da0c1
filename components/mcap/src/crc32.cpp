#include "crc32.hpp"

#include <algorithm>

#include <zlib.h>

namespace uavmot::mcap::detail {

uint32_t crc32_update(uint32_t crc, const void* data, size_t size) {
  const auto* p = static_cast<const Bytef*>(data);
  // zlib takes uInt lengths; feed large buffers in slices.
  while (size > 0) {
    const size_t n = std::min<size_t>(size, 1u << 30);
    crc = static_cast<uint32_t>(::crc32(crc, p, static_cast<uInt>(n)));
    p += n;
    size -= n;
  }
  return crc;
}

}  // namespace uavmot::mcap::detail
