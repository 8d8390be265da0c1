#pragma once
// Heap settings for processes that handle frames (megabytes each).

#include <cstddef>

namespace uavmot {

// By default glibc hands every freed buffer of a frame's size back to the kernel (mmap/munmap), so
// the next frame faults its pages in again: hundreds of page faults per 1080p frame and copy,
// costly in a VM. Buffers up to 32 MB (the most glibc allows) come from the heap instead, and up
// to 256 MB of free heap stays with the process, and the threads' arenas keep 64 MB of padding
// instead of unmapping a heap that has become free. run_app() calls this first.
void configure_allocator_for_frames();

// Faults `megabytes` of heap in now and leaves it free for the process's own allocations, so the
// first frames do not pay for first-touch page faults (on this machine a 1080p frame's first
// motion estimate took 80 ms instead of 49 ms, and the live chain's first frames queued up behind
// it). Needs configure_allocator_for_frames() (chunks below the mmap threshold, no trimming).
void prefault_heap(std::size_t megabytes);

}  // namespace uavmot
