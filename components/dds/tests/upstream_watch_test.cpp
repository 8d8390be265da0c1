#include "uavmot/dds/upstream_watch.hpp"

#include <gtest/gtest.h>

namespace uavmot::dds {
namespace {
using namespace std::chrono_literals;

TEST(UpstreamWatch, GivesUpOnlyAfterTheTimeoutWithoutAnyWriter) {
  const auto t0 = UpstreamWatch::Clock::time_point{} + 100s;
  UpstreamWatch watch(2.0, t0);
  EXPECT_FALSE(watch.gone(0, t0 + 1s));
  EXPECT_FALSE(watch.gone(0, t0 + 1999ms));
  EXPECT_TRUE(watch.gone(0, t0 + 2s));
}

TEST(UpstreamWatch, AMatchedWriterStartsTheCountAgain) {
  const auto t0 = UpstreamWatch::Clock::time_point{} + 100s;
  UpstreamWatch watch(2.0, t0);
  EXPECT_FALSE(watch.gone(1, t0 + 1500ms));  // a writer (e.g. a respawned upstream) came
  EXPECT_FALSE(watch.gone(0, t0 + 3s));      // 1.5 s since it was last seen
  EXPECT_TRUE(watch.gone(0, t0 + 3500ms));
}

TEST(UpstreamWatch, ZeroTimeoutWaitsForever) {
  const auto t0 = UpstreamWatch::Clock::time_point{} + 100s;
  UpstreamWatch watch(0.0, t0);
  EXPECT_FALSE(watch.gone(0, t0 + 100000s));
}

TEST(UpstreamWatch, MessageNamesTheInputsAndTheOption) {
  const std::string text = UpstreamWatch(60.0).message("uavmot/frames");
  EXPECT_NE(text.find("no writer of uavmot/frames for 60 s (--upstream-timeout)"), std::string::npos) << text;
}

}  // namespace
}  // namespace uavmot::dds
