#include "uavmot/replay/recording_info.hpp"

#include <filesystem>

#include <gtest/gtest.h>

#include "uavmot/build_paths/build_paths.hpp"
#include "uavmot/mcap/writer.hpp"

namespace uavmot::replay {
namespace {

std::string write_sample(const std::string& name, mcap::Compression compression) {
  const std::string dir = build_paths::binary_dir() + "/test_output/replay_info";
  std::filesystem::create_directories(dir);
  const std::string path = dir + "/" + name;
  std::filesystem::remove(path);
  std::filesystem::remove(path + ".tmp");
  mcap::WriterOptions options;
  options.compression = compression;
  mcap::Writer w(options);
  w.open(path);
  const auto s = w.add_schema("uavmot::msg::MotionEstimate", "omgidl", std::string("module uavmot { };"));
  const auto motion = w.add_channel(s, "uavmot/motion", "cdr", {{"topic", "uavmot/motion"}});
  const auto tracks = w.add_channel(w.add_schema("uavmot::msg::TrackList", "omgidl", std::string("x")), "uavmot/tracks", "cdr");
  const uint8_t payload[8] = {0, 1, 0, 0, 1, 2, 3, 4};
  const uint64_t t0 = 1'795'332'930'000'000'000ull;  // 2026-11-22 07:35:30 UTC
  for (uint32_t i = 0; i < 10; ++i) w.write(motion, i + 1, t0 + i * 250'000'000ull, t0, payload, sizeof(payload));
  for (uint32_t i = 0; i < 4; ++i) w.write(tracks, i + 1, t0 + i * 500'000'000ull, t0, payload, sizeof(payload));
  w.close();
  return path;
}

TEST(RecordingInfo, TopicsTypesCountsDurationCompression) {
  mcap::Reader r;
  r.open(write_sample("info.mcap", mcap::Compression::Lz4));
  const std::string info = recording_info(r);
  EXPECT_NE(info.find("Duration:          2.250s"), std::string::npos) << info;
  EXPECT_NE(info.find("Messages:          14"), std::string::npos) << info;
  EXPECT_NE(info.find("(lz4)"), std::string::npos) << info;
  EXPECT_NE(info.find("Topic: uavmot/motion | Type: uavmot::msg::MotionEstimate | Count: 10 | Serialization Format: cdr"),
            std::string::npos)
      << info;
  EXPECT_NE(info.find("Topic: uavmot/tracks | Type: uavmot::msg::TrackList | Count: 4"), std::string::npos) << info;
  EXPECT_NE(info.find("Start:             2026-11-22 07:35:30.000000000 UTC"), std::string::npos) << info;
  EXPECT_NE(info.find("End:               2026-11-22 07:35:32.250000000 UTC"), std::string::npos) << info;
  EXPECT_EQ(info.find("Damage"), std::string::npos) << info;
}

TEST(RecordingInfo, DamageIsNamedWithItsOffset) {
  const std::string path = write_sample("cut.mcap", mcap::Compression::None);
  std::filesystem::resize_file(path, std::filesystem::file_size(path) / 2);
  mcap::Reader r;
  r.open(path);
  const std::string info = recording_info(r);
  EXPECT_NE(info.find("Damage:"), std::string::npos) << info;
  EXPECT_NE(info.find("byte offset"), std::string::npos) << info;
}

TEST(RecordingInfo, TimeFormat) {
  EXPECT_EQ(format_time(1'000'000'001ull), "1970-01-01 00:00:01.000000001 UTC (1.000000001)");
}

}  // namespace
}  // namespace uavmot::replay
