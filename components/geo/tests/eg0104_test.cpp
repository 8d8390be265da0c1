#include "uavmot/geo/eg0104.hpp"

#include <gtest/gtest.h>

#include "test_data.hpp"
#include "uavmot/core/error.hpp"
#include "uavmot/geo/mpegts_klv.hpp"

namespace uavmot::geo {
namespace {

// aphill_short.ts carries EG 0104 (Predator universal set), not ST 0601: every one of its 48 KLV
// units has the key 06 0E 2B 34 02 01 01 01 0E 01 01 02 01 01 00 00.
//
// Expected values were obtained independently of this code:
//   ffmpeg -i data/aphill/aphill_short.ts -map 0:d -c copy -f data out.klv      (ffmpeg 5.1, Debian)
// then each KLV unit of out.klv was parsed by vidterra/misb.js st0104.parse (package.json version
// 0.1.30, git 52c3837, run from its source: the npm registry reachable here answers 404 for
// @vidterra/misb.js), which returns each element's key, name and value as hex; Node's
// Buffer.readDoubleBE / readFloatBE / readBigUInt64BE turned the hex into the numbers below.
struct Expected {
  std::size_t packet;
  std::uint64_t time_us;
  double sensor_lat, sensor_lon, sensor_alt;
  double roll, pitch, heading, hfov, vfov, slant_range, angle_to_north, obliquity;
  double center_lat, center_lon;
  double corner_lat[4], corner_lon[4];
};

const Expected kPacket0 = {0, 1221515219356000u, 38.252336, -77.366859, 1054.4000244140625,
                           1.851196050643921, 1.0821529626846313, -102.7880859375, 0.800000011920929, 0.6000000238418579,
                           1729.9217529296875, 124.57490539550781, -37.55388641357422,
                           38.245587237812856, -77.3537376710918,
                           {38.2456129065011, 38.24542062209943, 38.24556189473287, 38.245751465939605},
                           {-77.35352504925287, -77.35365917915622, -77.35394759255416, -77.35381503864505}};
const Expected kPacket47 = {47, 1221515220926000u, 38.252153, -77.367953, 1054.4000244140625,
                            1.3623050451278687, 0.6646729707717896, -102.28271484375, 0.800000011920929, 0.6000000238418579,
                            1757.33935546875, 123.12811279296875, -36.8697509765625,
                            38.24550494794651, -77.35428504306273,
                            {38.245531895246195, 38.24533639725656, 38.24547835818394, 38.24567106546695},
                            {-77.35406553503488, -77.35420099022265, -77.35450163523541, -77.3543678829648}};

void expect_packet(const UasMetadata& m, const Expected& e) {
  SCOPED_TRACE("packet " + std::to_string(e.packet));
  EXPECT_EQ(m.standard, MetadataStandard::kEg0104);
  EXPECT_EQ(m.precision_time_us, e.time_us);
  EXPECT_DOUBLE_EQ(*m.sensor_latitude_deg, e.sensor_lat);
  EXPECT_DOUBLE_EQ(*m.sensor_longitude_deg, e.sensor_lon);
  EXPECT_DOUBLE_EQ(*m.sensor_true_altitude_m, e.sensor_alt);
  EXPECT_DOUBLE_EQ(*m.platform_roll_deg, e.roll);
  EXPECT_DOUBLE_EQ(*m.platform_pitch_deg, e.pitch);
  EXPECT_DOUBLE_EQ(*m.platform_heading_deg, e.heading);
  EXPECT_DOUBLE_EQ(*m.sensor_hfov_deg, e.hfov);
  EXPECT_DOUBLE_EQ(*m.sensor_vfov_deg, e.vfov);
  EXPECT_DOUBLE_EQ(*m.slant_range_m, e.slant_range);
  EXPECT_DOUBLE_EQ(*m.sensor_angle_to_north_deg, e.angle_to_north);
  EXPECT_DOUBLE_EQ(*m.sensor_obliquity_deg, e.obliquity);
  EXPECT_DOUBLE_EQ(*m.frame_center_latitude_deg, e.center_lat);
  EXPECT_DOUBLE_EQ(*m.frame_center_longitude_deg, e.center_lon);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_DOUBLE_EQ(*m.corner_latitude_deg[i], e.corner_lat[i]) << "corner " << i + 1;
    EXPECT_DOUBLE_EQ(*m.corner_longitude_deg[i], e.corner_lon[i]) << "corner " << i + 1;
  }
  EXPECT_FALSE(m.checksum_ok.has_value());  // EG 0104 has none
  EXPECT_EQ(m.unknown_items, 1u);           // device designation ("ABCD")
  EXPECT_EQ(m.malformed_items, 0u);
}

TEST(Eg0104, AphillPacketsMatchMisbJs) {
  const MpegTsKlv ts = read_mpegts_klv(test::aphill_ts_path());
  ASSERT_EQ(ts.klv.size(), 48u);
  expect_packet(decode_eg0104(ts.klv[0].bytes), kPacket0);
  expect_packet(decode_eg0104(ts.klv[47].bytes), kPacket47);
  for (const KlvPacket& p : ts.klv) {
    const auto m = decode_uas_metadata(p.bytes);
    ASSERT_TRUE(m.has_value());
    EXPECT_EQ(m->standard, MetadataStandard::kEg0104);
  }
}

TEST(Eg0104, EveryTruncationIsAnInputError) {
  const MpegTsKlv ts = read_mpegts_klv(test::aphill_ts_path());
  ASSERT_FALSE(ts.klv.empty());
  const auto& bytes = ts.klv[0].bytes;
  for (std::size_t n = 0; n < bytes.size(); ++n) {
    EXPECT_THROW(decode_eg0104(std::span<const std::uint8_t>(bytes.data(), n)), InputError) << "cut at " << n;
  }
}

TEST(Eg0104, ShortenedSetCutsItsLastElement) {
  const MpegTsKlv ts = read_mpegts_klv(test::aphill_ts_path());
  auto bytes = ts.klv[0].bytes;
  ASSERT_EQ(bytes[16], 0x82);  // long-form length 0x0217
  bytes[18] = 0x16;            // 0x0216: the last element (corner 4 longitude) runs past the set
  EXPECT_THROW(decode_eg0104(bytes), InputError);
}

}  // namespace
}  // namespace uavmot::geo
