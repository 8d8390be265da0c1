#include "uavmot/dds/downlink_convert.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>

#include <gtest/gtest.h>

#include "uavmot/core/result_files.hpp"
#include "scratch_dir.hpp"

namespace uavmot::dds {
namespace {

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
  round_to_float32(track);  // as the tracker publishes it
  t.tracks = {track};
  p.tracks = t;
  return p;
}

TEST(DownlinkConvert, OneFrameRoundTripsHomographyAndTracksExactlyAndRegionsAsPrinted) {
  const FrameParts in = full_frame();
  std::string why;
  const auto out = from_msg(to_downlink_msg("uav2", 9, in), why);
  ASSERT_TRUE(out) << why;
  ASSERT_TRUE(out->motion && out->regions && out->tracks);
  EXPECT_EQ(out->motion->stream_id, "uav2");
  EXPECT_EQ(out->motion->frame_index, 9);
  EXPECT_EQ(out->motion->capture_time_ns, 360'000'000);
  EXPECT_EQ(out->motion->image_width, 1024);
  for (int i = 0; i < 9; ++i) EXPECT_EQ(out->motion->homography.val[i], in.motion->homography.val[i]) << i;
  EXPECT_EQ(out->motion->quality.inliers, 412u);
  EXPECT_NEAR(out->motion->quality.residual_px, 0.0731, 1e-7);
  EXPECT_TRUE(out->motion->features.empty());

  ASSERT_EQ(out->regions->size(), 1u);
  const PrintedRegion expected = printed_region(in.segmentation->regions[0]);
  const PrintedRegion& r = out->regions->front();
  EXPECT_EQ(r.x, expected.x);
  EXPECT_EQ(r.y, expected.y);
  EXPECT_EQ(r.width, expected.width);
  EXPECT_EQ(r.height, expected.height);
  EXPECT_EQ(r.score, 875);

  ASSERT_EQ(out->tracks->tracks.size(), 1u);
  const Track& t = out->tracks->tracks[0];
  EXPECT_EQ(t.id, 4'000'000'000ULL);
  EXPECT_EQ(t.state, TrackState::Coasting);
  EXPECT_EQ(t.box.cx, in.tracks->tracks[0].box.cx);
  EXPECT_EQ(t.box.cy, 300.25);
  EXPECT_EQ(t.box.angle_deg, -45.0);
  EXPECT_EQ(t.velocity[0], in.tracks->tracks[0].velocity[0]);
  EXPECT_EQ(t.velocity[1], in.tracks->tracks[0].velocity[1]);
  EXPECT_NEAR(t.box.cx, 512.0005, 1e-4);
  EXPECT_EQ(t.sigma_x, 0.0);
  EXPECT_TRUE(t.feature_ids.empty());
}

std::string read_all(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The ground writes what crossed the link; `uavmot process` writes the chain's own values. With
// numbers that sit on rounding edges (xxx.xxx5, -0.0004), the files must still be the same bytes.
TEST(DownlinkConvert, GroundFilesAreByteIdenticalToTheInProcessWriter) {
  const auto root = test_support::scratch_path("downlink_files");
  std::filesystem::remove_all(root);
  ResultFilesOptions options{(root / "process").string(), 25.0, 0.35, false, true, false};
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> pos(-20.0, 1100.0), side(0.5, 60.0), angle(-89.999, 90.0), v(-3.0, 3.0),
      tiny(-0.0006, 0.0006), score(0.0, 1.0);
  std::vector<FrameParts> frames;
  for (int k = 1; k <= 30; ++k) {
    FrameParts p = full_frame();
    p.motion->frame_index = k;
    p.segmentation->frame_index = k;
    p.segmentation->regions.clear();
    for (int i = 0; i < 60; ++i) {
      OrientedBox b{pos(rng), pos(rng), side(rng), side(rng), angle(rng)};
      if (i % 7 == 0) b.cx = std::round(b.cx) + 0.0005;  // a tie at the third decimal
      p.segmentation->regions.push_back({b, SegmentationMethod::Fusion, i % 5 == 0 ? 1.0 / 3.0 : score(rng), i});
    }
    p.tracks->frame_index = k;
    p.tracks->tracks.clear();
    for (int i = 0; i < 50; ++i) {
      Track t;
      t.id = static_cast<uint64_t>(i + 1);
      t.state = i % 3 == 0 ? TrackState::Tentative : TrackState::Confirmed;
      t.box = {pos(rng), pos(rng), side(rng), side(rng), angle(rng)};
      t.velocity = {i % 4 == 0 ? tiny(rng) : v(rng), tiny(rng)};  // -0.0000 in vx/vy
      round_to_float32(t);  // as the tracker publishes it
      p.tracks->tracks.push_back(t);
    }
    frames.push_back(p);
  }
  {
    ResultFilesWriter process(options);
    options.directory = (root / "ground").string();
    ResultFilesWriter ground(options);
    for (const FrameParts& p : frames) {
      process.write_motion(*p.motion);
      process.write_segmentation(*p.segmentation);
      process.write_tracks(*p.tracks);
      std::string why;
      const auto out = from_msg(to_downlink_msg("uav2", p.motion->frame_index, p), why);
      ASSERT_TRUE(out) << why;
      ground.write_motion(*out->motion);
      ground.write_printed_regions(p.motion->frame_index, *out->regions);
      ground.write_tracks(*out->tracks);
    }
    process.close({});
    ground.close({});
  }
  for (const char* file : {"tracks.txt", "tracks_obb.csv", "regions.txt", "homographies.txt"}) {
    const std::string expected = read_all(root / "process" / file);
    EXPECT_GT(expected.size(), 1000u) << file;
    EXPECT_EQ(read_all(root / "ground" / file), expected) << file;
  }
  EXPECT_NE(read_all(root / "process" / "tracks_obb.csv").find(",-0.0000"), std::string::npos) << "no negative zero tried";
  std::filesystem::remove_all(root);
}

TEST(DownlinkConvert, MissingPartsStayMissingAndOversizedIdsAreCounted) {
  FrameParts in = full_frame();
  in.segmentation.reset();
  in.tracks->tracks[0].id = (uint64_t{1} << 40);
  DownlinkDrops drops;
  std::string why;
  const auto out = from_msg(to_downlink_msg("uav2", 9, in, &drops), why);
  ASSERT_TRUE(out) << why;
  EXPECT_TRUE(out->motion.has_value());
  EXPECT_FALSE(out->regions.has_value());
  ASSERT_TRUE(out->tracks.has_value());
  EXPECT_TRUE(out->tracks->tracks.empty());
  EXPECT_EQ(drops.tracks, 1u);
  EXPECT_EQ(drops.regions, 0u);
  EXPECT_EQ(drops.inexact_tracks, 0u);
}

TEST(DownlinkConvert, TracksThatAreNotFloat32ValuesAreCounted) {
  FrameParts in = full_frame();
  in.tracks->tracks[0].box.cx = 512.0005;  // not rounded by a tracker
  DownlinkDrops drops;
  to_downlink_msg("uav2", 9, in, &drops);
  EXPECT_EQ(drops.inexact_tracks, 1u);
  EXPECT_EQ(drops.tracks, 0u);
}

TEST(DownlinkConvert, RegionsWhosePrintedNumbersDoNotFitAreCounted) {
  FrameParts in = full_frame();
  in.segmentation->regions.push_back(in.segmentation->regions[0]);
  in.segmentation->regions[1].score = 70.0;  // 70000 thousandths: beyond uint16
  DownlinkDrops drops;
  std::string why;
  const auto out = from_msg(to_downlink_msg("uav2", 9, in, &drops), why);
  ASSERT_TRUE(out) << why;
  EXPECT_EQ(out->regions->size(), 1u);
  EXPECT_EQ(drops.regions, 1u);
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
  sample.regions()[0].width(-1);
  EXPECT_FALSE(from_msg(sample, why));
  sample.regions()[0].width(1000);
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
