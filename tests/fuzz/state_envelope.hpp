#pragma once
// For the fuzz targets of saved states (state_codec::seal's envelope): the payload size and checksum
// made to match the bytes, so that the fuzzer reaches the payload's checks instead of stopping at the
// checksum. Bytes shorter than the envelope are left as they are.

#include <cstdint>
#include <cstring>
#include <vector>

#include "uavmot/core/checksum.hpp"
#include "uavmot/core/state_codec.hpp"

namespace uavmot::fuzz {

inline void match_envelope(std::vector<uint8_t>& bytes) {
  constexpr size_t kSizeAt = 8 + 4, kChecksumAt = kSizeAt + 8;  // after the magic and the version
  if (bytes.size() < state_codec::kEnvelopeBytes) return;
  const uint64_t payload = bytes.size() - state_codec::kEnvelopeBytes;
  const uint64_t checksum = fnv1a64(bytes.data() + state_codec::kEnvelopeBytes, payload);
  std::memcpy(bytes.data() + kSizeAt, &payload, sizeof payload);
  std::memcpy(bytes.data() + kChecksumAt, &checksum, sizeof checksum);
}

}  // namespace uavmot::fuzz
