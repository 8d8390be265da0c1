#include "uavmot/geo/chain_ground.hpp"

#include <gtest/gtest.h>

#include "test_data.hpp"
#include "uavmot/build_paths/build_paths.hpp"
#include "uavmot/core/error.hpp"

namespace uavmot::geo {
namespace {

constexpr double kAphillFps = 30000.0 / 1001.0;

TEST(ChainGround, AphillFromTheFirstFrame) {
  const ChainGround ground(read_flight_metadata(test::aphill_ts_path(), {720, 480}, kAphillFps));
  EXPECT_TRUE(ground.has_ground_mapping());
  const MetadataSummary s = ground.summary();
  EXPECT_EQ(s.packets, 48);
  EXPECT_EQ(s.standard, "EG 0104");
  EXPECT_EQ(s.bad_checksums, 0);
  EXPECT_EQ(s.frames_with_geometry, 48);
  ASSERT_TRUE(ground.median_gsd_m());
  EXPECT_DOUBLE_EQ(*ground.median_gsd_m(), *ground.flight().summary.median_gsd_m_per_px);
  // The image centre of frame 1 maps inside frame 1's footprint, near its frame centre.
  const auto p = ground.pixel_to_lat_lon()(1, 359.5, 239.5);
  ASSERT_TRUE(p);
  EXPECT_NEAR((*p)[0], 38.24557, 1e-4);
  EXPECT_NEAR((*p)[1], -77.35375, 1e-4);
  EXPECT_FALSE(ground.pixel_to_lat_lon()(0, 1, 1));
  EXPECT_FALSE(ground.pixel_to_lat_lon()(49, 1, 1));
}

// `--start 11`: chain frame 1 is input frame 11.
TEST(ChainGround, StartOffsetShiftsFrames) {
  FlightMetadata flight = read_flight_metadata(test::aphill_ts_path(), {720, 480}, kAphillFps);
  const ChainGround whole(flight);
  const ChainGround late(flight, 11);
  ASSERT_NE(late.frame(1), nullptr);
  EXPECT_EQ((*late.frame(1)->corners())[0].lat_deg, (*whole.frame(11)->corners())[0].lat_deg);
  EXPECT_EQ(late.frame(39), nullptr);  // input frame 49
  EXPECT_THROW(ChainGround(flight, 0), InvalidArgument);
}

TEST(ChainGround, NoMetadataNoMapping) {
  const ChainGround ground(read_flight_metadata(build_paths::data_dir() + "/aphill/aphill_240_1fps_crf32.mp4", {720, 480}, 1.0));
  EXPECT_FALSE(ground.has_ground_mapping());
  EXPECT_FALSE(ground.median_gsd_m());
  EXPECT_EQ(ground.summary().standard, "");
}

}  // namespace
}  // namespace uavmot::geo
