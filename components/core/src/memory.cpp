#include "uavmot/core/memory.hpp"

#include <malloc.h>

#include <cstdlib>
#include <vector>

namespace uavmot {

namespace {
constexpr int kMmapThreshold = 32 << 20;
constexpr std::size_t kChunk = 16 << 20;  // below the mmap threshold: from the heap, kept when freed
}  // namespace

void configure_allocator_for_frames() {
  mallopt(M_MMAP_THRESHOLD, kMmapThreshold);
  mallopt(M_TRIM_THRESHOLD, 256 << 20);
  // The threads' own arenas (the decoding and motion threads allocate frames and pyramids) give a
  // heap that has become free back to the kernel whatever the trim threshold, unless this much
  // padding is kept: at 4K, `uavmot process --threads 2` faulted in 3 800 pages a frame, 2.7 s of
  // system time over 100 frames, and ran at 14 fps instead of 16.5 (docs/benchmarks.md).
  mallopt(M_TOP_PAD, 64 << 20);
}

void prefault_heap(std::size_t megabytes) {
  std::vector<void*> chunks;
  for (std::size_t done = 0; done < megabytes << 20; done += kChunk) {
    void* chunk = std::malloc(kChunk);
    if (chunk == nullptr) break;
    // The first touch of a page is its fault; volatile so the compiler keeps writes it could
    // prove unused (the chunk is freed unread).
    auto* bytes = static_cast<volatile char*>(chunk);
    for (std::size_t i = 0; i < kChunk; i += 4096) bytes[i] = 0;
    chunks.push_back(chunk);
  }
  for (void* chunk : chunks) std::free(chunk);
}

}  // namespace uavmot
