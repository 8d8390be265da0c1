#include "uavmot/dds/chain_convert.hpp"

#include <cmath>

#include <gtest/gtest.h>

namespace uavmot::dds {
namespace {

MotionEstimate sample_motion() {
  MotionEstimate m;
  m.stream_id = "uav2";
  m.frame_index = 9;
  m.capture_time_ns = 360'000'000;
  m.image_width = 1024;
  m.image_height = 768;
  m.homography = Homography(1.0001, 0.0002, 3.14159265358979, -0.0003, 0.9998, -2.718281828459045, 1e-7, -2e-7, 1);
  m.quality = {true, 412, 0.0731};
  m.features = {{1, {10.123456789, 20.5}, {0.31, -0.01}, 0.02, 17, true}, {5, {300.0, 1.0 / 3.0}, {0, 0}, 0.01, 2, false}};
  return m;
}

TEST(ChainConvert, MotionRoundTripIsExact) {
  const auto in = sample_motion();
  std::string why;
  const auto out = from_msg(to_msg(in), why);
  ASSERT_TRUE(out) << why;
  EXPECT_EQ(out->stream_id, in.stream_id);
  EXPECT_EQ(out->frame_index, in.frame_index);
  EXPECT_EQ(out->capture_time_ns, in.capture_time_ns);
  EXPECT_EQ(out->image_width, 1024);
  EXPECT_EQ(out->image_height, 768);
  for (int i = 0; i < 9; ++i) EXPECT_EQ(out->homography.val[i], in.homography.val[i]);
  EXPECT_EQ(out->quality.inliers, 412u);
  EXPECT_EQ(out->quality.residual_px, 0.0731);
  ASSERT_EQ(out->features.size(), 2u);
  EXPECT_EQ(out->features[0].position.x, 10.123456789);
  EXPECT_EQ(out->features[1].position.y, 1.0 / 3.0);
  EXPECT_EQ(out->features[0].velocity[0], 0.31);
  EXPECT_EQ(out->features[0].age, 17u);
  EXPECT_TRUE(out->features[0].moving);
}

TEST(ChainConvert, SegmentationAndTracksRoundTripIsExact) {
  SegmentationResult s;
  s.stream_id = "uav1";
  s.frame_index = 3;
  s.clusters = {{4, {1.5, 2.5, 5.1, 15.2, -33.3}, {0.7, 0.1}, {1, 2, 3}}};
  s.regions = {{{1.25, 2.75, 5.0, 14.9, 89.9}, SegmentationMethod::Lbp, 0.875, 4}};
  std::string why;
  const auto s2 = from_msg(to_msg(s), why);
  ASSERT_TRUE(s2) << why;
  EXPECT_EQ(s2->clusters[0].box, s.clusters[0].box);
  EXPECT_EQ(s2->clusters[0].feature_ids, s.clusters[0].feature_ids);
  EXPECT_EQ(s2->regions[0].box, s.regions[0].box);
  EXPECT_EQ(s2->regions[0].method, SegmentationMethod::Lbp);
  EXPECT_EQ(s2->regions[0].cluster_id, 4);

  TrackList t;
  t.stream_id = "uav1";
  t.frame_index = 3;
  Track track;
  track.id = 12;
  track.state = TrackState::Coasting;
  track.box = {100.1, 200.2, 5.3, 15.4, -89.9};
  track.velocity = {1.5, -0.25};
  track.sigma_x = 0.3;
  track.sigma_angle_deg = 2.5;
  track.age = 40;
  track.frames_since_update = 2;
  track.feature_ids = {7, 8};
  t.tracks = {track};
  const auto t2 = from_msg(to_msg(t), why);
  ASSERT_TRUE(t2) << why;
  EXPECT_EQ(t2->tracks[0].box, track.box);
  EXPECT_EQ(t2->tracks[0].state, TrackState::Coasting);
  EXPECT_EQ(t2->tracks[0].velocity[1], -0.25);
  EXPECT_EQ(t2->tracks[0].sigma_angle_deg, 2.5);
  EXPECT_EQ(t2->tracks[0].feature_ids, track.feature_ids);
}

TEST(ChainConvert, MalformedSamplesAreRejectedWithAReason) {
  std::string why;
  auto m = to_msg(sample_motion());
  m.homography()[4] = NAN;
  EXPECT_FALSE(from_msg(m, why));
  EXPECT_NE(why.find("homography"), std::string::npos);

  m = to_msg(sample_motion());
  m.features()[1].vx(INFINITY);
  EXPECT_FALSE(from_msg(m, why));

  m = to_msg(sample_motion());
  m.features().resize(kMaxFeatures + 1);
  EXPECT_FALSE(from_msg(m, why));
  EXPECT_NE(why.find("exceed"), std::string::npos);

  m = to_msg(sample_motion());
  m.frame_index(0);
  EXPECT_FALSE(from_msg(m, why));

  SegmentationResult s;
  s.frame_index = 1;
  s.regions = {{{1, 2, -5, 10, 0}, SegmentationMethod::Fusion, 1.0, -1}};
  EXPECT_FALSE(from_msg(to_msg(s), why));

  SegmentationResult unknown_method;
  unknown_method.frame_index = 1;
  unknown_method.regions = {{{1, 2, 5, 10, 0}, SegmentationMethod::Fusion, 1.0, -1}};
  for (uint32_t method : {static_cast<uint32_t>(kSegmentationMethods.size()), 256u}) {  // 256: not cut to a byte
    auto ms = to_msg(unknown_method);
    ms.regions()[0].method(static_cast<msg::SegmentationMethod>(method));
    EXPECT_FALSE(from_msg(ms, why)) << method;
  }

  TrackList t;
  t.frame_index = 1;
  Track bad;
  bad.box = {NAN, 0, 1, 1, 0};
  t.tracks = {bad};
  EXPECT_FALSE(from_msg(to_msg(t), why));
}

// Core's list is generated from the IDL's enum (core_tests check the generator); here every method
// crosses the wire as its place in the list, which fastddsgen's enum numbers the same way.
TEST(ChainConvert, EveryMethodCrossesTheWireAsItsPlace) {
  static_assert(static_cast<int>(msg::SegmentationMethod::CLUSTERING) == static_cast<int>(SegmentationMethod::Clustering));
  static_assert(static_cast<int>(msg::SegmentationMethod::FUSION) == static_cast<int>(SegmentationMethod::Fusion));
  for (size_t i = 0; i < kSegmentationMethods.size(); ++i) {
    SegmentationResult s;
    s.frame_index = 1;
    s.regions = {{{1, 2, 5, 10, 0}, kSegmentationMethods[i], 1.0, -1}};
    const auto m = to_msg(s);
    EXPECT_EQ(static_cast<size_t>(m.regions()[0].method()), i);
    std::string why;
    const auto back = from_msg(m, why);
    ASSERT_TRUE(back) << to_string(kSegmentationMethods[i]) << ": " << why;
    EXPECT_EQ(back->regions[0].method, kSegmentationMethods[i]);
  }
}

}  // namespace
}  // namespace uavmot::dds
