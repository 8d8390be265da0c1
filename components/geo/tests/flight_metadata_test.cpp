#include "uavmot/geo/flight_metadata.hpp"

#include <cstdio>
#include <fstream>

#include <gtest/gtest.h>

#include "test_data.hpp"
#include "uavmot/build_paths/build_paths.hpp"
#include "uavmot/core/error.hpp"

namespace uavmot::geo {
namespace {

// The decoded frame rate of aphill_short.ts: 48 frames, 3003 ticks apart (ffprobe frame PTS).
constexpr double kAphillFps = 30000.0 / 1001.0;

TEST(FlightMetadata, AphillEveryFrameHasGeometry) {
  const FlightMetadata f = read_flight_metadata(test::aphill_ts_path(), {720, 480}, kAphillFps);
  EXPECT_EQ(f.summary.klv_units, 48u);
  EXPECT_EQ(f.summary.packets, 48u);
  EXPECT_EQ(f.summary.bad_checksum, 0u);  // EG 0104 carries no checksum
  EXPECT_EQ(f.summary.undecodable, 0u);
  ASSERT_EQ(f.frames.size(), 48u);
  EXPECT_EQ(f.summary.frames_with_geometry, 48u);
  ASSERT_TRUE(f.summary.median_gsd_m_per_px);
  std::printf("aphill_short.ts: median GSD %.4f m/px over %zu frames\n", *f.summary.median_gsd_m_per_px, f.summary.frames_with_geometry);
  EXPECT_GT(*f.summary.median_gsd_m_per_px, 0.02);
  EXPECT_LT(*f.summary.median_gsd_m_per_px, 0.1);

  // Frame 1 is at the first video PTS, 129003: the second KLV packet has that PTS exactly (the
  // first, 126000, comes before any frame); frame k then takes packet k.
  for (int k = 1; k <= 48; ++k) {
    const FrameGeometry* g = f.frame(k);
    ASSERT_NE(g, nullptr) << k;
    const std::size_t packet = std::min<std::size_t>(static_cast<std::size_t>(k), 47);
    EXPECT_DOUBLE_EQ((*g->corners())[0].lat_deg, *f.packets[packet].metadata.corner_latitude_deg[0]) << k;
  }
  EXPECT_EQ(f.frame(0), nullptr);
  EXPECT_EQ(f.frame(49), nullptr);
}

TEST(FlightMetadata, ExplicitFrameCountAndLatestPacketAtOrBefore) {
  // At 59.94 fps (ffprobe's r_frame_rate) frame k is 1501.5 ticks after frame k - 1: two frames
  // share each packet.
  const FlightMetadata f = read_flight_metadata(test::aphill_ts_path(), {720, 480}, 60000.0 / 1001.0, 10);
  ASSERT_EQ(f.frames.size(), 10u);
  EXPECT_DOUBLE_EQ((*f.frame(2)->corners())[0].lat_deg, (*f.frame(1)->corners())[0].lat_deg);
  EXPECT_NE((*f.frame(3)->corners())[0].lat_deg, (*f.frame(2)->corners())[0].lat_deg);
}

TEST(FlightMetadata, OtherInputsGiveAnEmptyResult) {
  const std::string jpg = build_paths::data_dir() + "/clif2007/jpg/000000-100006.jpg";
  EXPECT_TRUE(read_flight_metadata(jpg, {668, 1004}, 1.0).empty());
  EXPECT_TRUE(read_flight_metadata(build_paths::data_dir() + "/aphill/aphill_240_1fps_crf32.mp4", {360, 240}, 1.0).empty());
  EXPECT_TRUE(read_flight_metadata(build_paths::data_dir() + "/clif2007/jpg", {668, 1004}, 1.0).empty());
}

TEST(FlightMetadata, BadTsAndBadArguments) {
  const std::string path = build_paths::binary_dir() + "/geo_test_garbage.ts";
  {
    std::ofstream out(path, std::ios::binary);
    out << std::string(5000, 'x');
  }
  EXPECT_THROW(read_flight_metadata(path, {720, 480}, 30.0), InputError);
  EXPECT_THROW(read_flight_metadata("/nonexistent/clip.ts", {720, 480}, 30.0), InputError);
  EXPECT_THROW(read_flight_metadata(test::aphill_ts_path(), {720, 480}, 0.0), InvalidArgument);
  EXPECT_THROW(read_flight_metadata(test::aphill_ts_path(), {0, 480}, 30.0), InvalidArgument);
}

}  // namespace
}  // namespace uavmot::geo
