#include "uavmot/core/memory.hpp"

#include <sys/resource.h>

#include <cstdlib>

#include <gtest/gtest.h>

namespace uavmot {
namespace {

long minor_faults() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_minflt;
}

// Page faults of allocating and touching `bytes`.
long faults_of_touching(std::size_t bytes) {
  const long before = minor_faults();
  void* buffer = std::malloc(bytes);
  // Volatile writes, one per page: the compiler may drop a malloc + memset + free it can see through.
  auto* bytes_out = static_cast<volatile char*>(buffer);
  for (std::size_t i = 0; i < bytes; i += 4096) bytes_out[i] = 1;
  const long faults = minor_faults() - before;
  std::free(buffer);
  return faults;
}

TEST(Memory, APrefaultedHeapServesAFramesBuffersWithoutPageFaults) {
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
  GTEST_SKIP() << "the sanitizer's allocator replaces glibc's: no heap to reserve";
#endif
  configure_allocator_for_frames();
  constexpr std::size_t kFrame = 8 << 20;  // a 1080p frame as 4 bytes per pixel
  prefault_heap(64);
  // 2048 pages: touched fresh, each would fault once.
  EXPECT_LT(faults_of_touching(kFrame), 64);
  EXPECT_LT(faults_of_touching(2 * kFrame), 64) << "the reserve was handed back to the kernel";
}

}  // namespace
}  // namespace uavmot
