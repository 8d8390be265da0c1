#include "uavmot/core/cpu_priority.hpp"

#include <thread>

#include <gtest/gtest.h>

#include "uavmot/core/error.hpp"

namespace uavmot {
namespace {

TEST(CpuPriority, IdleReachesTheKernelAndThreadsStartedAfterwardsInheritIt) {
  // In a thread of its own, so the test runner's threads keep their priority.
  CpuPriority set{}, child{};
  std::thread([&] {
    set_cpu_priority(CpuPriority::Idle);
    set = current_cpu_priority();
    std::thread([&] { child = current_cpu_priority(); }).join();
  }).join();
  EXPECT_EQ(set, CpuPriority::Idle);
  EXPECT_EQ(child, CpuPriority::Idle) << "a library's thread started after the call would compete with the chain";
  EXPECT_EQ(current_cpu_priority(), CpuPriority::Normal);
}

TEST(CpuPriority, NamesParseAndUnknownOnesAreRefused) {
  EXPECT_EQ(parse_cpu_priority("idle"), CpuPriority::Idle);
  EXPECT_EQ(parse_cpu_priority("normal"), CpuPriority::Normal);
  EXPECT_STREQ(to_string(CpuPriority::Idle), "idle");
  EXPECT_THROW(parse_cpu_priority("low"), InvalidArgument);
}

}  // namespace
}  // namespace uavmot
