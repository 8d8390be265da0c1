#include "uavmot/dds/downlink_convert.hpp"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

namespace uavmot::dds {
namespace {

// float32 keeps a relative 6e-8: at 2000 px that is 1.2e-4 px.
constexpr double kFloatTolerance = 2e-4;

FrameParts full_frame() {
  FrameParts p;
  MotionEstimate m;
  m.stream_id = "uav2";
  m.frame_index = 9;
  m.capture_time_ns = 360'000'000;
  m.image_width = 1024;
  m.image_height = 768;
  m.homography = Homography(1.0001, 0.0002, 3.14159265358979, -0.0003, 0.9998, -2.718281828459045, 1e-7, -2e-7, 1);
  m.quality = {true, 412, 0.0731};
  m.features = {{1, {10.1, 20.5}, {0.31, -0.01}, 0.02, 17, true}};
  p.motion = m;
  SegmentationResult s;
  s.stream_id = "uav2";
  s.frame_index = 9;
  s.capture_time_ns = 360'000'000;
  s.clusters = {{4, {1.5, 2.5, 5.1, 15.2, -33.3}, {0.7, 0.1}, {1, 2, 3}}};
  s.regions = {{{1023.123456, 767.987654, 5.0, 14.9, 89.9}, SegmentationMethod::Lbp, 0.875, 4}};
  p.segmentation = s;
  TrackList t;
  t.stream_id = "uav2";
  t.frame_index = 9;
  t.capture_time_ns = 360'000'000;
  Track track;
  track.id = 4'000'000'000ULL;  // still fits 32 bits
  track.state = TrackState::Coasting;
  track.box = {512.0005, 300.25, 1.8, 4.5, -45.0};
  track.velocity = {1.23456, -0.000123};
  track.sigma_x = 2.0;
  track.feature_ids = {1, 2};
  t.tracks = {track};
  p.tracks = t;
  return p;
}

TEST(DownlinkConvert, OneFrameRoundTripsHomographyExactlyAndBoxesWithinFloatPrecision) {
  const FrameParts in = full_frame();
  std::string why;
  const auto out = from_msg(to_downlink_msg("uav2", 9, in), why);
  ASSERT_TRUE(out) << why;
  ASSERT_TRUE(out->motion && out->segmentation && out->tracks);
  EXPECT_EQ(out->motion->stream_id, "uav2");
  EXPECT_EQ(out->motion->frame_index, 9);
  EXPECT_EQ(out->motion->capture_time_ns, 360'000'000);
  EXPECT_EQ(out->motion->image_width, 1024);
  for (int i = 0; i < 9; ++i) EXPECT_EQ(out->motion->homography.val[i], in.motion->homography.val[i]) << i;
  EXPECT_EQ(out->motion->quality.inliers, 412u);
  EXPECT_NEAR(out->motion->quality.residual_px, 0.0731, 1e-7);
  EXPECT_TRUE(out->motion->features.empty());

  EXPECT_TRUE(out->segmentation->clusters.empty());
  ASSERT_EQ(out->segmentation->regions.size(), 1u);
  EXPECT_NEAR(out->segmentation->regions[0].box.cx, 1023.123456, kFloatTolerance);
  EXPECT_NEAR(out->segmentation->regions[0].box.cy, 767.987654, kFloatTolerance);
  EXPECT_EQ(out->segmentation->regions[0].method, SegmentationMethod::Lbp);
  EXPECT_EQ(out->segmentation->regions[0].score, 0.875);

  ASSERT_EQ(out->tracks->tracks.size(), 1u);
  const Track& t = out->tracks->tracks[0];
  EXPECT_EQ(t.id, 4'000'000'000ULL);
  EXPECT_EQ(t.state, TrackState::Coasting);
  EXPECT_NEAR(t.box.cx, 512.0005, kFloatTolerance);
  EXPECT_NEAR(t.velocity[0], 1.23456, 1e-6);
  EXPECT_NEAR(t.velocity[1], -0.000123, 1e-9);
  EXPECT_EQ(t.sigma_x, 0.0);
  EXPECT_TRUE(t.feature_ids.empty());
}

TEST(DownlinkConvert, MissingPartsStayMissingAndOversizedIdsAreCounted) {
  FrameParts in = full_frame();
  in.segmentation.reset();
  in.tracks->tracks[0].id = (uint64_t{1} << 40);
  uint64_t dropped = 0;
  std::string why;
  const auto out = from_msg(to_downlink_msg("uav2", 9, in, &dropped), why);
  ASSERT_TRUE(out) << why;
  EXPECT_TRUE(out->motion.has_value());
  EXPECT_FALSE(out->segmentation.has_value());
  ASSERT_TRUE(out->tracks.has_value());
  EXPECT_TRUE(out->tracks->tracks.empty());
  EXPECT_EQ(dropped, 1u);
}

TEST(DownlinkConvert, RejectsMalformedSamples) {
  std::string why;
  auto sample = to_downlink_msg("uav1", 1, full_frame());
  sample.frame_index(0);
  EXPECT_FALSE(from_msg(sample, why));

  sample = to_downlink_msg("uav1", 1, full_frame());
  sample.motion().homography()[2] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(from_msg(sample, why));

  sample = to_downlink_msg("uav1", 1, full_frame());
  sample.regions()[0].box().width(-1.0F);
  EXPECT_FALSE(from_msg(sample, why));
  sample.regions()[0].box().width(1.0F);
  sample.regions()[0].method(9);
  EXPECT_FALSE(from_msg(sample, why));

  sample = to_downlink_msg("uav1", 1, full_frame());
  sample.tracks()[0].vx(std::numeric_limits<float>::infinity());
  EXPECT_FALSE(from_msg(sample, why));
  EXPECT_NE(why.find("track"), std::string::npos);

  sample = to_downlink_msg("uav1", 1, full_frame());
  sample.has_tracks(false);  // tracks without the flag: inconsistent
  EXPECT_FALSE(from_msg(sample, why));
}

}  // namespace
}  // namespace uavmot::dds
