#pragma once
// FNV-1a 64-bit: a cheap, dependency-free checksum to prove frames arrive bit-identical.

#include <cstddef>
#include <cstdint>

namespace uavmot {

uint64_t fnv1a64(const void* data, size_t size, uint64_t seed = 14695981039346656037ULL);

}  // namespace uavmot
