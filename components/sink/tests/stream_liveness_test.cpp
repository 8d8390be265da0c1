#include "uavmot/sink/stream_liveness.hpp"

#include <gtest/gtest.h>

namespace uavmot::sink {
namespace {
using namespace std::chrono_literals;
using Clock = StreamLiveness::Clock;

TEST(StreamLiveness, SilentStreamIsLostOnceAndTheOthersStayAlive) {
  StreamLiveness live(2.0);
  const Clock::time_point t0{};
  live.heard("uav1", 1, t0);
  live.heard("uav2", 1, t0);
  live.heard("uav2", 7, t0 + 1s);
  live.heard("uav1", 5, t0 + 2500ms);
  EXPECT_TRUE(live.newly_lost(t0 + 2900ms).empty()) << "uav2 silent 1.9 s, uav1 0.4 s";
  EXPECT_EQ(live.newly_lost(t0 + 3100ms), std::vector<std::string>{"uav2"});
  EXPECT_TRUE(live.newly_lost(t0 + 3200ms).empty()) << "reported once";
  EXPECT_TRUE(live.is_lost("uav2"));
  EXPECT_FALSE(live.is_lost("uav1"));
  EXPECT_EQ(live.lost_count(), 1u);
  EXPECT_EQ(live.last_frame("uav2"), 7);
}

TEST(StreamLiveness, LostStreamThatSpeaksAgainIsBack) {
  StreamLiveness live(1.0);
  const Clock::time_point t0{};
  live.heard("uav1", 3, t0);
  ASSERT_EQ(live.newly_lost(t0 + 2s).size(), 1u);
  EXPECT_TRUE(live.heard("uav1", 4, t0 + 3s));
  EXPECT_FALSE(live.is_lost("uav1"));
  EXPECT_FALSE(live.heard("uav1", 5, t0 + 3100ms)) << "back only once";
  EXPECT_EQ(live.newly_lost(t0 + 5s), std::vector<std::string>{"uav1"}) << "and can be lost again";
}

TEST(StreamLiveness, EndedStreamIsNeverLost) {
  StreamLiveness live(1.0);
  const Clock::time_point t0{};
  live.heard("uav1", 9, t0);
  live.ended("uav1");
  EXPECT_TRUE(live.newly_lost(t0 + 1h).empty());
}

TEST(StreamLiveness, NoTimeoutNeverLoses) {
  StreamLiveness live(0.0);
  live.heard("uav1", 1, Clock::time_point{});
  EXPECT_TRUE(live.newly_lost(Clock::time_point{} + 24h).empty());
  EXPECT_EQ(live.last_frame("unknown"), 0);
}

}  // namespace
}  // namespace uavmot::sink
