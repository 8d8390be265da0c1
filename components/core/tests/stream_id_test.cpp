#include "uavmot/core/stream_id.hpp"

#include <gtest/gtest.h>

namespace uavmot {
namespace {

TEST(StreamId, SafePathComponentsOnly) {
  for (const char* ok : {"uav1", "UAV-2_a.b", "a", "...", "x..y"}) EXPECT_TRUE(is_valid_stream_id(ok)) << ok;
  EXPECT_TRUE(is_valid_stream_id(std::string(64, 'a')));
  for (const char* bad : {"", ".", "..", "../../etc", "/tmp/x", "a/b", "a b", "a\\b", "uav1\n", "é"}) {
    EXPECT_FALSE(is_valid_stream_id(bad)) << bad;
  }
  EXPECT_FALSE(is_valid_stream_id(std::string(65, 'a')));
  EXPECT_FALSE(is_valid_stream_id(std::string("a\0b", 3)));
  EXPECT_EQ(stream_id_problem("/tmp/x"), "stream id with a character other than A-Z a-z 0-9 . _ -");
}

TEST(StreamId, PrintableForLogs) {
  EXPECT_EQ(printable_stream_id("uav1"), "'uav1'");
  EXPECT_EQ(printable_stream_id("a\nb'"), "'a\\x0ab\\x27'");
  EXPECT_EQ(printable_stream_id(std::string(100, 'x')), "'" + std::string(80, 'x') + "' (100 characters)");
}

}  // namespace
}  // namespace uavmot
