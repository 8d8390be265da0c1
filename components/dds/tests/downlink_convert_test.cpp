#include "uavmot/dds/downlink_convert.hpp"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

namespace uavmot::dds {
namespace {

// float32 keeps a relative 6e-8: at 2000 px that is 1.2e-4 px.
constexpr double kFloatTolerance = 2e-4;

TEST(DownlinkConvert, MotionSummaryKeepsTheHomographyExactAndDropsFeatures) {
  MotionEstimate m;
  m.stream_id = "uav2";
  m.frame_index = 9;
  m.capture_time_ns = 360'000'000;
  m.image_width = 1024;
  m.image_height = 768;
  m.homography = Homography(1.0001, 0.0002, 3.14159265358979, -0.0003, 0.9998, -2.718281828459045, 1e-7, -2e-7, 1);
  m.quality = {true, 412, 0.0731};
  m.features = {{1, {10.1, 20.5}, {0.31, -0.01}, 0.02, 17, true}};
  std::string why;
  const auto out = from_msg(to_downlink_msg(m), why);
  ASSERT_TRUE(out) << why;
  EXPECT_EQ(out->stream_id, "uav2");
  EXPECT_EQ(out->frame_index, 9);
  EXPECT_EQ(out->capture_time_ns, 360'000'000);
  EXPECT_EQ(out->image_width, 1024);
  for (int i = 0; i < 9; ++i) EXPECT_EQ(out->homography.val[i], m.homography.val[i]) << i;
  EXPECT_TRUE(out->quality.valid);
  EXPECT_EQ(out->quality.inliers, 412u);
  EXPECT_NEAR(out->quality.residual_px, 0.0731, 1e-7);
  EXPECT_TRUE(out->features.empty());
}

TEST(DownlinkConvert, RegionsAndTracksRoundTripWithinFloatPrecision) {
  SegmentationResult s;
  s.stream_id = "uav1";
  s.frame_index = 3;
  s.clusters = {{4, {1.5, 2.5, 5.1, 15.2, -33.3}, {0.7, 0.1}, {1, 2, 3}}};
  s.regions = {{{1023.123456, 767.987654, 5.0, 14.9, 89.9}, SegmentationMethod::Lbp, 0.875, 4}};
  std::string why;
  const auto s2 = from_msg(to_downlink_msg(s), why);
  ASSERT_TRUE(s2) << why;
  EXPECT_TRUE(s2->clusters.empty());
  ASSERT_EQ(s2->regions.size(), 1u);
  EXPECT_NEAR(s2->regions[0].box.cx, 1023.123456, kFloatTolerance);
  EXPECT_NEAR(s2->regions[0].box.cy, 767.987654, kFloatTolerance);
  EXPECT_NEAR(s2->regions[0].box.angle_deg, 89.9, kFloatTolerance);
  EXPECT_EQ(s2->regions[0].method, SegmentationMethod::Lbp);
  EXPECT_EQ(s2->regions[0].score, 0.875);

  TrackList t;
  t.stream_id = "uav1";
  t.frame_index = 4;
  Track track;
  track.id = (uint64_t{1} << 40) + 7;  // ids stay 64-bit
  track.state = TrackState::Coasting;
  track.box = {512.0005, 300.25, 1.8, 4.5, -45.0};
  track.velocity = {1.23456, -0.000123};
  track.sigma_x = 2.0;
  track.feature_ids = {1, 2};
  t.tracks = {track};
  const auto t2 = from_msg(to_downlink_msg(t), why);
  ASSERT_TRUE(t2) << why;
  ASSERT_EQ(t2->tracks.size(), 1u);
  EXPECT_EQ(t2->tracks[0].id, track.id);
  EXPECT_EQ(t2->tracks[0].state, TrackState::Coasting);
  EXPECT_NEAR(t2->tracks[0].box.cx, 512.0005, kFloatTolerance);
  EXPECT_NEAR(t2->tracks[0].velocity[0], 1.23456, 1e-6);
  EXPECT_NEAR(t2->tracks[0].velocity[1], -0.000123, 1e-9);
  EXPECT_EQ(t2->tracks[0].sigma_x, 0.0);
  EXPECT_TRUE(t2->tracks[0].feature_ids.empty());
}

TEST(DownlinkConvert, RejectsMalformedSamples) {
  std::string why;
  msg::MotionSummary motion;
  motion.frame_index(0);
  EXPECT_FALSE(from_msg(motion, why));
  motion.frame_index(1);
  auto h = motion.homography();
  h[2] = std::numeric_limits<double>::quiet_NaN();
  motion.homography(h);
  EXPECT_FALSE(from_msg(motion, why));

  msg::RegionList regions;
  regions.frame_index(1);
  msg::CompactRegion r;
  r.box().width(-1.0F);
  regions.regions().push_back(r);
  EXPECT_FALSE(from_msg(regions, why));
  regions.regions()[0].box().width(1.0F);
  regions.regions()[0].method(9);
  EXPECT_FALSE(from_msg(regions, why));

  msg::CompactTrackList tracks;
  tracks.frame_index(1);
  msg::CompactTrack t;
  t.vx(std::numeric_limits<float>::infinity());
  tracks.tracks().push_back(t);
  EXPECT_FALSE(from_msg(tracks, why));
  EXPECT_NE(why.find("track"), std::string::npos);
}

}  // namespace
}  // namespace uavmot::dds
