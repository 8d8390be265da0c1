#include "uavmot/geo/klv.hpp"

#include <gtest/gtest.h>

namespace uavmot::geo {
namespace {

using V = std::vector<std::uint8_t>;

TEST(Klv, BerLengthShortAndLongForm) {
  const V short_form = {0x7F};
  EXPECT_EQ(read_ber_length(short_form, 0)->value, 127u);
  EXPECT_EQ(read_ber_length(short_form, 0)->size, 1u);
  const V long_form = {0x82, 0x02, 0x17};
  EXPECT_EQ(read_ber_length(long_form, 0)->value, 535u);
  EXPECT_EQ(read_ber_length(long_form, 0)->size, 3u);
}

TEST(Klv, BerLengthRejectsCutIndefiniteAndHuge) {
  EXPECT_FALSE(read_ber_length(V{}, 0));
  EXPECT_FALSE(read_ber_length(V{0x82, 0x01}, 0));  // cut
  EXPECT_FALSE(read_ber_length(V{0x80}, 0));        // indefinite
  EXPECT_FALSE(read_ber_length(V{0x89, 1, 2, 3, 4, 5, 6, 7, 8, 9}, 0));  // 9 bytes
  EXPECT_FALSE(read_ber_length(V{0x01}, 5));        // past the end
}

TEST(Klv, BerOidTags) {
  EXPECT_EQ(read_ber_oid(V{0x41}, 0)->value, 65u);
  EXPECT_EQ(read_ber_oid(V{0x81, 0x02}, 0)->value, 130u);
  EXPECT_EQ(read_ber_oid(V{0x81, 0x02}, 0)->size, 2u);
  EXPECT_FALSE(read_ber_oid(V{0x81}, 0));                    // cut
  EXPECT_FALSE(read_ber_oid(V{0x81, 0x81, 0x81, 0x81, 0x01}, 0));  // longer than 4 bytes
}

V unit(std::uint8_t last_key_byte, std::size_t value_size) {
  V u = {0x06, 0x0E, 0x2B, 0x34, 0x02, 0x0B, 0x01, 0x01, 0x0E, 0x01, 0x03, 0x01, 0x01, 0x00, 0x00, last_key_byte};
  u.push_back(static_cast<std::uint8_t>(value_size));
  u.insert(u.end(), value_size, 0xAB);
  return u;
}

TEST(Klv, SplitSkipsJunkAndStopsAtACutUnit) {
  V bytes = {0x00, 0x01, 0x02};  // e.g. a metadata AU cell header
  const V a = unit(0, 5), b = unit(1, 3), cut = unit(2, 40);
  bytes.insert(bytes.end(), a.begin(), a.end());
  bytes.insert(bytes.end(), b.begin(), b.end());
  bytes.insert(bytes.end(), cut.begin(), cut.begin() + 30);
  const KlvSplit split = split_klv_units(bytes);
  ASSERT_EQ(split.units.size(), 2u);
  EXPECT_EQ(split.units[0].offset, 3u);
  EXPECT_EQ(split.units[0].size, a.size());
  EXPECT_EQ(split.units[0].value_size, 5u);
  EXPECT_EQ(split.units[1].offset, 3 + a.size());
  EXPECT_EQ(split.truncated_units, 1u);
  EXPECT_EQ(split.skipped_bytes, 3u + 30u);
}

}  // namespace
}  // namespace uavmot::geo
