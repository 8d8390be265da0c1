// Writing then reading gives back every message, byte for byte, in log-time order.

#include <gtest/gtest.h>

#include <filesystem>

#include "test_util.hpp"
#include "uavmot/mcap/reader.hpp"
#include "uavmot/mcap/writer.hpp"

namespace uavmot::mcap {
namespace {

using test::Written;

class RoundTrip : public ::testing::TestWithParam<Compression> {};

TEST_P(RoundTrip, EveryMessageComesBackIdenticalInLogTimeOrder) {
  const auto dir = test::temp_dir("round_trip");
  const std::string path = (dir / "rec.mcap").string();
  WriterOptions options;
  options.compression = GetParam();
  options.chunk_size = 16 * 1024;  // many chunks, overlapping in time (jittered log times)
  std::vector<Written> written;
  {
    Writer writer(options);
    writer.open(path);
    EXPECT_TRUE(std::filesystem::exists(path + ".tmp"));
    EXPECT_FALSE(std::filesystem::exists(path));
    written = test::write_recording(writer, test::spec(600));
    writer.add_metadata({"recorder", {{"command", "uavmot record --out rec.mcap"}}});
    writer.close();
  }
  EXPECT_FALSE(std::filesystem::exists(path + ".tmp"));

  Reader reader;
  reader.open(path);
  EXPECT_TRUE(reader.indexed());
  EXPECT_FALSE(reader.damage().has_value());
  EXPECT_TRUE(reader.notes().empty());
  EXPECT_EQ(reader.header().library, "uavmot");

  const auto expected = test::in_log_time_order(written);
  const auto got = test::read_all(reader, {});
  ASSERT_EQ(got.size(), expected.size());
  EXPECT_TRUE(test::equal_messages(got, expected));

  const Statistics& st = reader.statistics();
  EXPECT_EQ(st.message_count, 600u);
  EXPECT_EQ(st.schema_count, 2u);
  EXPECT_EQ(st.channel_count, 3u);
  EXPECT_EQ(st.metadata_count, 1u);
  ASSERT_EQ(st.channel_message_counts.size(), 3u);
  for (const auto& [id, count] : st.channel_message_counts) EXPECT_EQ(count, 200u) << "channel " << id;
  EXPECT_EQ(st.message_start_time, expected.front().log_time);
  EXPECT_EQ(st.message_end_time, expected.back().log_time);

  const auto chunks = reader.chunks();
  EXPECT_EQ(chunks.size(), st.chunk_count);
  EXPECT_GT(chunks.size(), 20u);
  for (const ChunkInfo& c : chunks) {
    EXPECT_EQ(c.compression, compression_name(GetParam()));
    if (GetParam() != Compression::None) {
      EXPECT_LT(c.compressed_size, c.uncompressed_size);
    }
  }

  ASSERT_EQ(reader.schemas().size(), 2u);
  EXPECT_EQ(reader.schemas().at(1).name, "test::A");
  EXPECT_EQ(reader.schemas().at(1).encoding, "omgidl");
  const std::string idl(reader.schemas().at(1).data.begin(), reader.schemas().at(1).data.end());
  EXPECT_EQ(idl, "struct A { long x; };");
  ASSERT_EQ(reader.channels().size(), 3u);
  const Channel& b = reader.channels().at(2);
  EXPECT_EQ(b.topic, "test/b");
  EXPECT_EQ(b.schema_id, 2);
  EXPECT_EQ(b.message_encoding, "cdr");
  EXPECT_EQ(b.metadata.at("reliability"), "RELIABLE");
  ASSERT_EQ(reader.metadata().size(), 1u);
  EXPECT_EQ(reader.metadata()[0].entries.at("command"), "uavmot record --out rec.mcap");
  std::filesystem::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(Compressions, RoundTrip,
                         ::testing::Values(Compression::None, Compression::Lz4, Compression::Zstd),
                         test::compression_test_name);

TEST(RoundTrip, TimeRangeUsesTheChunkIndexAndReturnsExactlyThatRange) {
  const auto dir = test::temp_dir("seek");
  const std::string path = (dir / "rec.mcap").string();
  WriterOptions options;
  options.chunk_size = 8 * 1024;
  std::vector<Written> written;
  {
    Writer writer(options);
    writer.open(path);
    written = test::write_recording(writer, test::spec(3000, 1000, true));
    writer.close();
  }
  Reader reader;
  reader.open(path);
  const size_t total_chunks = reader.chunks().size();
  ASSERT_GT(total_chunks, 50u);

  const auto all = test::in_log_time_order(written);
  ReadFilter filter;
  filter.start_time = all[1200].log_time;
  filter.end_time = all[1500].log_time;  // exclusive
  std::vector<Written> expected;
  for (const Written& w : all) {
    if (w.log_time >= filter.start_time && w.log_time < filter.end_time) expected.push_back(w);
  }
  ASSERT_GT(expected.size(), 250u);

  MessageCursor cursor = reader.messages(filter);
  std::vector<Written> got;
  MessageView m;
  while (cursor.next(m)) {
    got.push_back({m.channel->id, m.sequence, m.log_time, m.publish_time, {m.data, m.data + m.size}, 0});
  }
  EXPECT_TRUE(test::equal_messages(got, expected));
  // Only the chunks overlapping the range were read: 300 of 3000 messages need about a tenth.
  EXPECT_LT(cursor.chunks_loaded(), total_chunks / 5);
  EXPECT_GT(cursor.chunks_loaded(), 0u);

  // Topic filter: only test/b, all of it.
  ReadFilter topic_filter;
  topic_filter.topics = {"test/b"};
  const auto only_b = test::read_all(reader, topic_filter);
  std::vector<Written> expected_b;
  for (const Written& w : all) {
    if (w.channel == 2) expected_b.push_back(w);
  }
  EXPECT_TRUE(test::equal_messages(only_b, expected_b));
  std::filesystem::remove_all(dir);
}

TEST(RoundTrip, LargeFramesSpanOneChunkEach) {
  const auto dir = test::temp_dir("large");
  const std::string path = (dir / "rec.mcap").string();
  Writer writer(test::options(Compression::Lz4, 1024 * 1024));
  writer.open(path);
  const uint16_t ch = writer.add_channel(0, "frames", "cdr");
  std::vector<std::vector<uint8_t>> frames;
  for (int i = 0; i < 4; ++i) {
    std::vector<uint8_t> f(3 * 1024 * 1024);
    for (size_t k = 0; k < f.size(); ++k) f[k] = static_cast<uint8_t>((k / 1920 + k % 1920 + i * 7) & 0xff);
    writer.write(ch, static_cast<uint32_t>(i), 100 + i, 100 + i, f.data(), f.size());
    EXPECT_EQ(writer.pending_bytes(), 0u) << "a frame larger than chunk_size is written at once";
    frames.push_back(std::move(f));
  }
  writer.close();
  Reader reader;
  reader.open(path);
  EXPECT_EQ(reader.chunks().size(), 4u);
  size_t i = 0;
  reader.for_each_message({}, [&](const MessageView& m) {
    EXPECT_EQ(m.schema, nullptr);
    EXPECT_TRUE(m.size == frames[i].size() && std::equal(frames[i].begin(), frames[i].end(), m.data));
    ++i;
    return true;
  });
  EXPECT_EQ(i, 4u);
  std::filesystem::remove_all(dir);
}

TEST(RoundTrip, ZstdWorkerThreadsWriteTheSameMessages) {
  const auto dir = test::temp_dir("zstd_threads");
  const std::string path = (dir / "rec.mcap").string();
  WriterOptions options = test::options(Compression::Zstd, 256 * 1024);
  options.compression_threads = 2;
  std::vector<Written> written;
  {
    Writer writer(options);
    writer.open(path);
    written = test::write_recording(writer, test::spec(400, 20000));
    writer.close();
  }
  Reader reader;
  reader.open(path);
  EXPECT_FALSE(reader.damage());
  EXPECT_GT(reader.chunks().size(), 5u);
  EXPECT_TRUE(test::equal_messages(test::read_all(reader, {}), test::in_log_time_order(written)));
  std::filesystem::remove_all(dir);
}

TEST(RoundTrip, EmptyRecordingIsValid) {
  const auto dir = test::temp_dir("empty_rec");
  const std::string path = (dir / "rec.mcap").string();
  {
    Writer writer;
    writer.open(path);
    writer.add_channel(writer.add_schema("t::T", "omgidl", std::string("struct T { long a; };")), "t", "cdr");
    writer.close();
  }
  Reader reader;
  reader.open(path);
  EXPECT_TRUE(reader.indexed());
  EXPECT_FALSE(reader.damage());
  EXPECT_EQ(reader.statistics().message_count, 0u);
  EXPECT_EQ(reader.channels().size(), 1u);
  EXPECT_TRUE(test::read_all(reader, {}).empty());
  std::filesystem::remove_all(dir);
}

TEST(Writer, RejectsUnknownIdsAndDeduplicatesSchemas) {
  const auto dir = test::temp_dir("writer_ids");
  Writer writer;
  writer.open((dir / "rec.mcap").string());
  const uint16_t a = writer.add_schema("t::T", "omgidl", std::string("struct T { long a; };"));
  EXPECT_EQ(writer.add_schema("t::T", "omgidl", std::string("struct T { long a; };")), a);
  EXPECT_NE(writer.add_schema("t::U", "omgidl", std::string("struct U { long a; };")), a);
  EXPECT_THROW(writer.add_channel(77, "x", "cdr"), InvalidArgument);
  const uint8_t byte = 1;
  EXPECT_THROW(writer.write(5, 0, 0, 0, &byte, 1), InvalidArgument);
  writer.close();
  EXPECT_THROW(writer.write(1, 0, 0, 0, &byte, 1), InvalidArgument);
  std::filesystem::remove_all(dir);
}

TEST(Writer, NeverOverwritesALeftoverTemporaryFile) {
  const auto dir = test::temp_dir("leftover");
  const std::string path = (dir / "rec.mcap").string();
  test::write_file(path + ".tmp", {1, 2, 3});  // a crashed recording's file
  Writer writer;
  try {
    writer.open(path);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("rec.mcap.tmp: already exists"), std::string::npos) << e.what();
  }
  EXPECT_EQ(test::read_file(path + ".tmp"), (std::vector<uint8_t>{1, 2, 3}));
  std::filesystem::remove_all(dir);
}

TEST(Writer, UnwritablePathIsAClearError) {
  Writer writer;
  try {
    writer.open("/nonexistent_dir_uavmot/rec.mcap");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent_dir_uavmot/rec.mcap.tmp"), std::string::npos) << e.what();
  }
}

TEST(Compression, NamesFollowTheSpec) {
  EXPECT_EQ(compression_name(Compression::None), "");
  EXPECT_EQ(compression_name(Compression::Lz4), "lz4");
  EXPECT_EQ(compression_name(Compression::Zstd), "zstd");
  EXPECT_EQ(parse_compression("none"), Compression::None);
  EXPECT_EQ(parse_compression("zstd"), Compression::Zstd);
  EXPECT_THROW(parse_compression("gzip"), InputError);
}

}  // namespace
}  // namespace uavmot::mcap
