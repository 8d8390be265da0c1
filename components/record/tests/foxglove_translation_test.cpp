// uavmot samples -> Foxglove messages (CDR), as record and the live bridge make them: the channel
// each topic feeds, JPEG frames passed through untouched, raw frames as RawImage, end-of-stream
// markers and malformed samples give no message.

#include <gtest/gtest.h>

#include <algorithm>

#include "uavmot/dds/chain_convert.hpp"
#include "uavmot/dds/downlink_convert.hpp"
#include "uavmot/dds/frame_convert.hpp"
#include "uavmot/foxglove/schemas.hpp"
#include "uavmot/record/foxglove_translation.hpp"

namespace uavmot::record {
namespace {

uint32_t u32_at(const std::vector<uint8_t>& bytes, size_t offset) {
  uint32_t v;
  std::memcpy(&v, bytes.data() + offset, 4);
  return v;
}

TEST(FoxgloveTranslation, ChannelsPerTopic) {
  FoxgloveOptions jpeg;
  FoxgloveOptions raw;
  raw.image_format = foxglove::ImageFormat::Raw;
  EXPECT_EQ(foxglove_channel("uavmot/frames", jpeg)->schema_name, foxglove::kCompressedImageSchema);
  EXPECT_EQ(foxglove_channel("uavmot/frames", raw)->schema_name, foxglove::kRawImageSchema);
  EXPECT_EQ(foxglove_channel("uavmot/frames", raw)->topic, "uavmot/foxglove/image");
  EXPECT_EQ(foxglove_channel("uavmot/tracks", jpeg)->topic, "uavmot/foxglove/tracks");
  EXPECT_EQ(foxglove_channel("uavmot/segmentation", jpeg)->topic, "uavmot/foxglove/regions");
  EXPECT_EQ(foxglove_channel("uavmot/motion", jpeg)->topic, "uavmot/foxglove/features");
  EXPECT_FALSE(foxglove_channel("uavmot/health", jpeg));
}

TEST(FoxgloveTranslation, JpegFramesPassThroughUnchanged) {
  msg::Frame sample;
  sample.stream_id("uav1");
  sample.frame_index(4);
  sample.capture_time_ns(3'000'000'007);
  sample.encoding(msg::Encoding::JPEG);
  sample.width(8);
  sample.height(8);
  sample.data({0xff, 0xd8, 1, 2, 3, 0xff, 0xd9});
  std::string why;
  const auto bytes = to_foxglove(sample, FoxgloveOptions{}, why);
  ASSERT_TRUE(bytes) << why;
  EXPECT_EQ(u32_at(*bytes, 4), 3u);  // timestamp.sec
  EXPECT_EQ(u32_at(*bytes, 8), 7u);  // timestamp.nsec
  EXPECT_EQ(u32_at(*bytes, 12), 5u);  // frame_id "uav1" + NUL, then padding to 4
  const std::vector<uint8_t> jpeg = {0xff, 0xd8, 1, 2, 3, 0xff, 0xd9};
  EXPECT_EQ(u32_at(*bytes, 24), jpeg.size());
  EXPECT_TRUE(std::equal(jpeg.begin(), jpeg.end(), bytes->begin() + 28));
}

TEST(FoxgloveTranslation, RawFramesAsRawImage) {
  Frame frame{"uav1", 1, 0, cv::Mat(6, 10, CV_8UC1, cv::Scalar(9))};
  auto sample = dds::to_msg(frame);
  FoxgloveOptions options;
  options.image_format = foxglove::ImageFormat::Raw;
  std::string why;
  const auto bytes = to_foxglove(sample, options, why);
  ASSERT_TRUE(bytes) << why;
  EXPECT_EQ(u32_at(*bytes, 24), 10u);  // width, after the timestamp and "uav1" (padded to 4)
  EXPECT_EQ(u32_at(*bytes, 28), 6u);
  EXPECT_EQ(bytes->size(), 4u + 8 + 12 + 8 + 12 + 4 + 4 + 60);  // mono8 string, step, data length, pixels
}

TEST(FoxgloveTranslation, EndOfStreamAndMalformedSamplesGiveNoMessage) {
  std::string why = "stale";
  auto end = dds::end_of_stream_frame("uav1", 10);
  EXPECT_FALSE(to_foxglove(end, FoxgloveOptions{}, why));
  EXPECT_TRUE(why.empty());

  msg::Frame bad;
  bad.stream_id("uav1");
  bad.frame_index(1);
  bad.encoding(msg::Encoding::MONO8);
  bad.width(100);
  bad.height(100);
  bad.data(std::vector<uint8_t>(10));  // far fewer than 100 x 100 pixels
  EXPECT_FALSE(to_foxglove(bad, FoxgloveOptions{}, why));
  EXPECT_FALSE(why.empty());
}

TEST(FoxgloveTranslation, TracksBecomeAnnotations) {
  TrackList list;
  list.stream_id = "uav1";
  list.frame_index = 2;
  Track t;
  t.id = 5;
  t.state = TrackState::Confirmed;
  t.box = {50, 50, 4, 8, 0};
  list.tracks.push_back(t);
  auto sample = dds::to_msg(list);
  std::string why;
  const auto bytes = to_foxglove(sample, FoxgloveOptions{}, why);
  ASSERT_TRUE(bytes) << why;
  EXPECT_EQ(u32_at(*bytes, 4), 0u);  // no circles
  EXPECT_EQ(u32_at(*bytes, 8), 1u);  // one polygon
  const std::string text(bytes->begin(), bytes->end());
  EXPECT_NE(text.find("#5 0.0 px/f"), std::string::npos);
}

TEST(FoxgloveTranslation, DownlinkResultsBecomeTrackAndRegionAnnotations) {
  FoxgloveOptions options;
  EXPECT_EQ(foxglove_channel("uavmot/downlink/results", options)->topic, "uavmot/foxglove/downlink/results");
  EXPECT_EQ(foxglove_channel("uavmot/downlink/preview", options)->schema_name, foxglove::kCompressedImageSchema);
  dds::FrameParts parts;
  parts.segmentation = SegmentationResult{};
  parts.segmentation->regions.push_back({{40, 30, 4, 8, 0}, SegmentationMethod::Fusion, 0.5, -1});
  parts.tracks = TrackList{};
  Track t;
  t.id = 9;
  t.state = TrackState::Confirmed;
  t.box = {40, 30, 4, 8, 0};
  parts.tracks->tracks.push_back(t);
  auto sample = dds::to_downlink_msg("uav1", 3, parts);
  std::string why;
  const auto bytes = to_foxglove(sample, options, why);
  ASSERT_TRUE(bytes) << why;
  EXPECT_EQ(u32_at(*bytes, 4), 0u);  // no circles
  EXPECT_EQ(u32_at(*bytes, 8), 2u);  // the region's rectangle and the track's polygon
  const std::string text(bytes->begin(), bytes->end());
  EXPECT_NE(text.find("#9 0.0 px/f"), std::string::npos);
}

}  // namespace
}  // namespace uavmot::record
