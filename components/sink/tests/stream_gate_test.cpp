#include "uavmot/sink/stream_gate.hpp"

#include <gtest/gtest.h>

namespace uavmot::sink {
namespace {

TEST(StreamGate, FirstValidIdBindsOneStreamRun) {
  StreamGate gate(1);
  EXPECT_FALSE(gate.admit("t", "../../etc"));
  EXPECT_FALSE(gate.admit("t", "/tmp/x"));
  EXPECT_FALSE(gate.admit("t", ".."));
  EXPECT_FALSE(gate.admit("t", std::string(65, 'a')));
  EXPECT_TRUE(gate.bound().empty()) << "an invalid id binds nothing";
  EXPECT_TRUE(gate.would_admit("uav1"));
  EXPECT_TRUE(gate.admit("t", "uav1"));
  EXPECT_TRUE(gate.admit("t", "uav1"));
  EXPECT_FALSE(gate.would_admit("uav2"));
  EXPECT_FALSE(gate.admit("t", "uav2")) << "a second id must not replace the first";
  EXPECT_EQ(gate.bound(), std::set<std::string>{"uav1"});
  EXPECT_EQ(gate.refused(), 5u);
}

TEST(StreamGate, EndOfStreamOnlyOfABoundStream) {
  StreamGate gate(2);
  EXPECT_FALSE(gate.admit_end("t", "uav1")) << "an end before any sample binds nothing";
  EXPECT_TRUE(gate.bound().empty());
  EXPECT_TRUE(gate.admit("t", "uav1"));
  EXPECT_FALSE(gate.admit_end("t", "uav2"));
  EXPECT_FALSE(gate.admit_end("t", "../x"));
  EXPECT_TRUE(gate.admit_end("t", "uav1"));
}

TEST(StreamGate, UpToNStreamsThenRefused) {
  StreamGate gate(2);
  EXPECT_TRUE(gate.admit("t", "a"));
  EXPECT_TRUE(gate.admit("t", "b"));
  EXPECT_FALSE(gate.admit("t", "c"));
  EXPECT_EQ(gate.bound(), (std::set<std::string>{"a", "b"}));
}

TEST(StreamGate, ExpectedIdsOnly) {
  StreamGate gate(1, {"uav7"});
  EXPECT_FALSE(gate.admit("t", "uav1")) << "not configured: refused even while the run is unbound";
  EXPECT_TRUE(gate.admit("t", "uav7"));
}

TEST(StreamGate, CheckDoesNotBind) {
  StreamGate gate(1);
  EXPECT_EQ(gate.check("t", "uav1"), StreamGate::Verdict::Unbound);
  EXPECT_EQ(gate.check("t", "../x"), StreamGate::Verdict::Refused);
  EXPECT_TRUE(gate.bound().empty());
  ASSERT_TRUE(gate.admit("t", "uav1"));
  EXPECT_EQ(gate.check("t", "uav1"), StreamGate::Verdict::Bound);
  EXPECT_EQ(gate.check("t", "uav2"), StreamGate::Verdict::Refused);
  EXPECT_EQ(gate.refused(), 2u);
}

TEST(StreamGate, ManyMadeUpIdsAreCountedWithBoundedMemory) {
  StreamGate gate(1);
  ASSERT_TRUE(gate.admit("t", "uav1"));
  for (int i = 0; i < 10000; ++i) gate.admit("t", "x" + std::to_string(i));
  EXPECT_EQ(gate.refused(), 10000u);
  gate.log_summary();
}

}  // namespace
}  // namespace uavmot::sink
