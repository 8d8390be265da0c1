#include "uavmot/geo/misb0601.hpp"

#include <gtest/gtest.h>

#include "test_data.hpp"
#include "uavmot/core/error.hpp"

namespace uavmot::geo {
namespace {

using test::from_hex;

constexpr double kS16 = 65534.0;       // 2^16 - 2: signed 16-bit maps
constexpr double kU16 = 65535.0;       // 2^16 - 1: unsigned 16-bit maps
constexpr double kS32 = 4294967294.0;  // 2^32 - 2
constexpr double kU32 = 4294967295.0;  // 2^32 - 1

// The hand-made packet (test_data.hpp), decoded by hand: each raw integer is read off the hex
// (tag, length, value) and put through ST 0601's mapping for its tag.
TEST(St0601, HandDecodedPacket) {
  const auto bytes = from_hex(test::kHandMade0601Hex);
  const UasMetadata m = decode_st0601(bytes);
  EXPECT_EQ(m.standard, MetadataStandard::kSt0601);
  EXPECT_EQ(m.precision_time_us, 1221825232000000u);           // 02 08 0004573E5AEE5400
  EXPECT_EQ(m.ls_version, 17);                                 // 41 01 11
  EXPECT_DOUBLE_EQ(*m.platform_heading_deg, 16384 * 360.0 / kU16);  // 05 02 4000
  EXPECT_DOUBLE_EQ(*m.platform_pitch_deg, -1000 * 40.0 / kS16);     // 06 02 FC18
  EXPECT_FALSE(m.platform_roll_deg.has_value());               // 07 02 8000: the error indicator
  EXPECT_DOUBLE_EQ(*m.sensor_latitude_deg, 913000000 * 180.0 / kS32);    // 0D 04 366B4640
  EXPECT_DOUBLE_EQ(*m.sensor_longitude_deg, -923000000 * 360.0 / kS32);  // 0E 04 C8FC2340
  EXPECT_DOUBLE_EQ(*m.sensor_true_altitude_m, 10000 * 19900.0 / kU16 - 900.0);  // 0F 02 2710
  EXPECT_DOUBLE_EQ(*m.sensor_hfov_deg, 300 * 180.0 / kU16);  // 10 02 012C
  EXPECT_DOUBLE_EQ(*m.sensor_vfov_deg, 200 * 180.0 / kU16);  // 11 02 00C8
  EXPECT_DOUBLE_EQ(*m.sensor_relative_azimuth_deg, 1073741824.0 * 360.0 / kU32);  // 12 04 40000000
  EXPECT_DOUBLE_EQ(*m.sensor_relative_elevation_deg, -300000000 * 360.0 / kS32);  // 13 04 EE1E5D00
  EXPECT_DOUBLE_EQ(*m.sensor_relative_roll_deg, 0.0);                             // 14 04 00000000
  EXPECT_DOUBLE_EQ(*m.slant_range_m, 1500000 * 5000000.0 / kU32);                 // 15 04 0016E360
  EXPECT_DOUBLE_EQ(*m.target_width_m, 20 * 10000.0 / kU16);                       // 16 02 0014
  EXPECT_DOUBLE_EQ(*m.frame_center_latitude_deg, 912700000 * 180.0 / kS32);      // 17 04 3666B260
  EXPECT_DOUBLE_EQ(*m.frame_center_longitude_deg, -923100000 * 360.0 / kS32);    // 18 04 C8FA9CA0
  EXPECT_DOUBLE_EQ(*m.frame_center_elevation_m, 5000 * 19900.0 / kU16 - 900.0);  // 19 02 1388
  // 1A..21: offset corners lat/lon of points 1-4, int16 * 0.15 / (2^16 - 2).
  const int offsets[4][2] = {{100, -200}, {-150, -120}, {-90, 210}, {140, 160}};
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_DOUBLE_EQ(*m.offset_corner_latitude_deg[i], offsets[i][0] * 0.15 / kS16) << i;
    EXPECT_DOUBLE_EQ(*m.offset_corner_longitude_deg[i], offsets[i][1] * 0.15 / kS16) << i;
  }
  // 52..59 (82-89): full corners, int32 like tags 13/14.
  const double corners[4][2] = {{913700000, -925100000}, {911200000, -924300000}, {911800000, -921000000}, {914100000, -921500000}};
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_DOUBLE_EQ(*m.corner_latitude_deg[i], corners[i][0] * 180.0 / kS32) << i;
    EXPECT_DOUBLE_EQ(*m.corner_longitude_deg[i], corners[i][1] * 360.0 / kS32) << i;
  }
  EXPECT_EQ(m.unknown_items, 1u);  // 81 02 01 07: tag 130 as a two-byte BER-OID, not read here
  EXPECT_EQ(m.error_values, 1u);   // the roll
  EXPECT_EQ(m.malformed_items, 0u);
  EXPECT_EQ(m.checksum_stored, 0x144A);  // 01 02 144A
  EXPECT_EQ(m.checksum_ok, true);
}

// The same packet through an independent decoder: vidterra/misb.js st0601.parse (package.json
// version 0.1.30, git 52c3837; run from its source because the npm registry reachable here
// answers 404 for @vidterra/misb.js):
//   node -e "const {st0601}=require('./misb.js'); for (const v of st0601.parse(HEX, {}))
//            console.log(v.key, v.name, v.value)"
// misb.js reads tag 7's 0x8000 as -50.0015 (it ignores ST 0601's error indicator); the rest agree.
TEST(St0601, HandMadePacketMatchesMisbJs) {
  const UasMetadata m = decode_st0601(from_hex(test::kHandMade0601Hex));
  EXPECT_NEAR(*m.platform_heading_deg, 90.0013733119707, 1e-12);
  EXPECT_NEAR(*m.platform_pitch_deg, -0.6103701895199443, 1e-12);
  EXPECT_NEAR(*m.sensor_latitude_deg, 38.26338799589473, 1e-12);
  EXPECT_NEAR(*m.sensor_longitude_deg, -77.36496630933367, 1e-12);
  EXPECT_NEAR(*m.sensor_true_altitude_m, 2136.5453574425883, 1e-9);
  EXPECT_NEAR(*m.sensor_hfov_deg, 0.8239871824216068, 1e-12);
  EXPECT_NEAR(*m.sensor_vfov_deg, 0.5493247882810712, 1e-12);
  EXPECT_NEAR(*m.sensor_relative_azimuth_deg, 90.00000002095476, 1e-12);
  EXPECT_NEAR(*m.sensor_relative_elevation_deg, -25.145709526327323, 1e-12);
  EXPECT_NEAR(*m.slant_range_m, 1746.229827810598, 1e-9);
  EXPECT_NEAR(*m.target_width_m, 3.051804379339284, 1e-12);
  EXPECT_NEAR(*m.frame_center_latitude_deg, 38.25081514113157, 1e-12);
  EXPECT_NEAR(*m.frame_center_longitude_deg, -77.37334821250911, 1e-12);
  EXPECT_NEAR(*m.frame_center_elevation_m, 618.2726787212941, 1e-9);
  EXPECT_NEAR(*m.offset_corner_latitude_deg[0], 0.00022888882106997244, 1e-15);
  EXPECT_NEAR(*m.offset_corner_longitude_deg[3], 0.0003662221137119698, 1e-15);
  EXPECT_NEAR(*m.corner_latitude_deg[0], 38.29272465700876, 1e-12);
  EXPECT_NEAR(*m.corner_longitude_deg[0], -77.54098627601796, 1e-12);
  EXPECT_NEAR(*m.corner_latitude_deg[3], 38.309488463359656, 1e-12);
  EXPECT_NEAR(*m.corner_longitude_deg[3], -77.23923776170204, 1e-12);
  EXPECT_EQ(*m.checksum_stored, 5194);
}

// MISB's own example packet (ST 0601), values as misb.js prints them (command above).
TEST(St0601, MisbExamplePacketMatchesMisbJs) {
  const UasMetadata m = decode_st0601(from_hex(test::kMisbExample0601Hex));
  EXPECT_EQ(m.precision_time_us, 1231798102000000u);
  EXPECT_NEAR(*m.platform_heading_deg, 159.97436484321355, 1e-12);
  EXPECT_NEAR(*m.platform_pitch_deg, -0.43153172399060225, 1e-12);
  EXPECT_NEAR(*m.platform_roll_deg, 3.4058656575212893, 1e-12);
  EXPECT_NEAR(*m.sensor_latitude_deg, 60.176822966978335, 1e-12);
  EXPECT_NEAR(*m.sensor_longitude_deg, 128.42675904204452, 1e-12);
  EXPECT_NEAR(*m.sensor_true_altitude_m, 14190.719462882429, 1e-9);
  EXPECT_NEAR(*m.sensor_hfov_deg, 144.5712977798123, 1e-12);
  EXPECT_NEAR(*m.sensor_vfov_deg, 152.64362554360264, 1e-12);
  EXPECT_NEAR(*m.sensor_relative_azimuth_deg, 160.71921143697557, 1e-12);
  EXPECT_NEAR(*m.sensor_relative_elevation_deg, -168.79232483394085, 1e-12);
  EXPECT_NEAR(*m.sensor_relative_roll_deg, 0.0, 1e-12);
  EXPECT_NEAR(*m.slant_range_m, 68590.98329874477, 1e-7);
  EXPECT_NEAR(*m.target_width_m, 722.8198672465096, 1e-9);
  EXPECT_NEAR(*m.frame_center_latitude_deg, -10.542388633146132, 1e-12);
  EXPECT_NEAR(*m.frame_center_longitude_deg, 29.15789012292302, 1e-12);
  EXPECT_NEAR(*m.frame_center_elevation_m, 3216.0372320134275, 1e-9);
  EXPECT_EQ(m.ls_version, 6);
  EXPECT_EQ(m.checksum_stored, 43587);
  EXPECT_EQ(m.checksum_ok, true);
  EXPECT_FALSE(m.corner_latitude_deg[0].has_value());
  EXPECT_FALSE(m.offset_corner_latitude_deg[0].has_value());
  EXPECT_EQ(m.unknown_items, 6u);  // tags 3, 10, 11, 12 (text), 48 (security set), 94 (MIIS id)
}

TEST(St0601, ChecksumMismatchIsReportedNotThrown) {
  auto bytes = from_hex(test::kHandMade0601Hex);
  bytes[46] ^= 0x01;  // inside tag 13's value (0D 04 at bytes 43-44)
  const UasMetadata m = decode_st0601(bytes);
  EXPECT_EQ(m.checksum_ok, false);
  EXPECT_EQ(m.checksum_stored, 0x144A);
  EXPECT_NE(m.checksum_computed, 0x144A);
  EXPECT_TRUE(m.sensor_latitude_deg.has_value());  // still decoded: the caller decides

  auto stored = from_hex(test::kHandMade0601Hex);
  stored.back() ^= 0xFF;  // the stored sum itself
  EXPECT_EQ(decode_st0601(stored).checksum_ok, false);
}

TEST(St0601, ChecksumFollowsTheStandardSum) {
  // Bytes at even offsets go in the high byte: 0x06 0x0E -> 0x060E.
  const std::vector<std::uint8_t> two = {0x06, 0x0E};
  EXPECT_EQ(st0601_checksum(two), 0x060E);
  const std::vector<std::uint8_t> wrap = {0xFF, 0xFF, 0x00, 0x02};
  EXPECT_EQ(st0601_checksum(wrap), 0x0001);  // 0xFFFF + 0x0002, 16 bits
}

TEST(St0601, EveryTruncationIsAnInputError) {
  const auto bytes = from_hex(test::kHandMade0601Hex);
  for (std::size_t n = 0; n < bytes.size(); ++n) {
    const std::span<const std::uint8_t> cut(bytes.data(), n);
    EXPECT_THROW(decode_st0601(cut), InputError) << "cut at " << n;
  }
}

TEST(St0601, BrokenItemLengthIsAnInputErrorWithThePosition) {
  auto bytes = from_hex(test::kHandMade0601Hex);
  // Tag 65's length byte (key 16 + length 81 B5 + tag 2's 10 bytes + its tag byte) becomes a 4-byte
  // long form: 0x11050240 bytes, past the end.
  bytes[29] = 0x84;
  try {
    decode_st0601(bytes);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("tag 65"), std::string::npos) << e.what();
  }
}

TEST(St0601, WrongSizeValueIsSkippedAndCounted) {
  // Key, length 9: tag 13 with a 3-byte value, then the checksum item.
  std::vector<std::uint8_t> bytes(kSt0601Key.begin(), kSt0601Key.end());
  const std::vector<std::uint8_t> body = {0x0D, 0x03, 0x01, 0x02, 0x03, 0x01, 0x02};
  bytes.push_back(static_cast<std::uint8_t>(body.size() + 2));
  bytes.insert(bytes.end(), body.begin(), body.end());
  const std::uint16_t sum = st0601_checksum(bytes);
  bytes.push_back(static_cast<std::uint8_t>(sum >> 8));
  bytes.push_back(static_cast<std::uint8_t>(sum & 0xFF));
  const UasMetadata m = decode_st0601(bytes);
  EXPECT_FALSE(m.sensor_latitude_deg.has_value());
  EXPECT_EQ(m.malformed_items, 1u);
  EXPECT_EQ(m.checksum_ok, true);
}

TEST(St0601, OtherKeyIsAnInputErrorAndNotUasMetadata) {
  auto bytes = from_hex(test::kHandMade0601Hex);
  bytes[5] = 0x01;
  EXPECT_THROW(decode_st0601(bytes), InputError);
  EXPECT_FALSE(decode_uas_metadata(bytes).has_value());
}

}  // namespace
}  // namespace uavmot::geo
