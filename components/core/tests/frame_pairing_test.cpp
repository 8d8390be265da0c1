#include "uavmot/core/frame_pairing.hpp"

#include <string>

#include <gtest/gtest.h>

namespace uavmot {
namespace {

TEST(FramePairing, ReleasesPairsInFrameOrder) {
  // Each side arrives in order, but the two sides interleave arbitrarily.
  FramePairing<int, std::string> pairing;
  pairing.add_first(1, 10);
  pairing.add_first(2, 20);
  EXPECT_FALSE(pairing.pop());
  pairing.add_second(1, "a");
  pairing.add_second(2, "b");
  auto p1 = pairing.pop();
  ASSERT_TRUE(p1);
  EXPECT_EQ(p1->index, 1);
  EXPECT_EQ(p1->first, 10);
  EXPECT_EQ(p1->second, "a");
  auto p2 = pairing.pop();
  ASSERT_TRUE(p2);
  EXPECT_EQ(p2->index, 2);
  EXPECT_FALSE(pairing.pop());
  EXPECT_EQ(pairing.dropped(), 0u);
}

TEST(FramePairing, DropsIndicesThatCanNoLongerComplete) {
  FramePairing<int, int> pairing;
  pairing.add_first(1, 1);   // its partner never comes
  pairing.add_second(2, 2);  // nor this one's
  pairing.add_first(3, 3);
  pairing.add_second(3, 3);
  auto p = pairing.pop();
  ASSERT_TRUE(p);
  EXPECT_EQ(p->index, 3);
  EXPECT_EQ(pairing.dropped(), 2u);
  EXPECT_EQ(pairing.pending(), 0u);
}

}  // namespace
}  // namespace uavmot
