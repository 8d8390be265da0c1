// recover(): a crashed recorder's .tmp (chunks, no summary) becomes a valid indexed file.

#include <gtest/gtest.h>

#include <filesystem>

#include "test_util.hpp"
#include "uavmot/mcap/reader.hpp"
#include "uavmot/mcap/recover.hpp"
#include "uavmot/mcap/writer.hpp"

namespace uavmot::mcap {
namespace {

using test::Written;

// Writes `total` messages and copies the .tmp file, as a crash would leave it, after `crash_after`.
struct Crashed {
  std::vector<Written> flushed;  // the messages in chunks already written at the crash
  size_t written_before_crash = 0;
};

Crashed record_and_crash(const std::string& path, const std::string& crash_copy, size_t total, size_t crash_after,
                         Compression compression) {
  Crashed c;
  Writer writer(test::options(compression, 4 * 1024));
  writer.open(path);
  const uint16_t schema = writer.add_schema("t::T", "omgidl", std::string("struct T { sequence<octet> d; };"));
  const uint16_t a = writer.add_channel(schema, "t/a", "cdr", {{"topic", "t/a"}});
  const uint16_t b = writer.add_channel(schema, "t/b", "cdr", {{"topic", "t/b"}});
  writer.add_metadata({"recorder", {{"version", "1"}}});
  std::vector<Written> all;
  size_t flushed_count = 0;
  for (size_t i = 0; i < total; ++i) {
    Written w;
    w.channel = i % 2 ? b : a;
    w.sequence = static_cast<uint32_t>(i);
    w.log_time = 5000 + i * 10;
    w.publish_time = w.log_time;
    w.data.assign(100 + (i * 37) % 400, static_cast<uint8_t>(i));
    writer.write(w.channel, w.sequence, w.log_time, w.publish_time, w.data.data(), w.data.size());
    all.push_back(std::move(w));
    if (writer.pending_bytes() == 0) flushed_count = all.size();
    if (i + 1 == crash_after) {
      std::filesystem::copy_file(writer.temporary_path(), crash_copy, std::filesystem::copy_options::overwrite_existing);
      c.written_before_crash = all.size();
      c.flushed.assign(all.begin(), all.begin() + static_cast<ptrdiff_t>(flushed_count));
    }
  }
  writer.close();
  return c;
}

class Recover : public ::testing::TestWithParam<Compression> {};

TEST_P(Recover, CrashedTemporaryFileBecomesValidWithEveryCompleteChunk) {
  const auto dir = test::temp_dir("recover");
  const std::string crashed = (dir / "flight.mcap.tmp").string();
  const Crashed c = record_and_crash((dir / "other.mcap").string(), crashed, 400, 333, GetParam());
  ASSERT_GT(c.flushed.size(), 100u);
  ASSERT_LT(c.flushed.size(), c.written_before_crash) << "the crash should lose the open chunk";

  {
    Reader damaged;
    damaged.open(crashed);
    ASSERT_TRUE(damaged.damage().has_value());
    EXPECT_NE(damaged.damage()->description.find("without a DataEnd"), std::string::npos);
    EXPECT_FALSE(damaged.indexed());
    EXPECT_EQ(damaged.statistics().message_count, c.flushed.size());
    EXPECT_EQ(damaged.statistics().channel_count, 2u);
    EXPECT_EQ(damaged.statistics().schema_count, 1u);
    EXPECT_EQ(damaged.statistics().metadata_count, 1u);
  }

  const std::string out = (dir / "flight.mcap").string();
  const RecoverResult result = recover(crashed, out);
  EXPECT_EQ(result.messages, c.flushed.size());
  EXPECT_EQ(result.channels, 2u);
  EXPECT_EQ(result.schemas, 1u);
  ASSERT_EQ(result.damage.size(), 1u);
  EXPECT_FALSE(std::filesystem::exists(out + ".recovering"));

  Reader reader;
  reader.open(out);
  EXPECT_TRUE(reader.indexed());
  EXPECT_FALSE(reader.damage().has_value());
  EXPECT_TRUE(test::equal_messages(test::read_all(reader, {}), c.flushed));
  EXPECT_EQ(reader.statistics().message_count, c.flushed.size());
  EXPECT_EQ(reader.channels().at(2).topic, "t/b");
  EXPECT_EQ(reader.channels().at(2).metadata.at("topic"), "t/b");
  ASSERT_EQ(reader.metadata().size(), 1u);
  EXPECT_EQ(reader.metadata()[0].name, "recorder");
  ASSERT_FALSE(reader.chunks().empty());
  EXPECT_EQ(reader.chunks()[0].compression, compression_name(GetParam()));  // kept from the input
  std::filesystem::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(Compressions, Recover,
                         ::testing::Values(Compression::None, Compression::Lz4, Compression::Zstd),
                         test::compression_test_name);

TEST(Recover, InPlaceOnTheTemporaryName) {
  const auto dir = test::temp_dir("recover_in_place");
  const std::string path = (dir / "flight.mcap").string();
  const std::string crashed = path + ".tmp";
  const Crashed c = record_and_crash((dir / "x.mcap").string(), crashed, 200, 150, Compression::Zstd);
  // `uavmot record --recover flight.mcap` reads flight.mcap.tmp and writes flight.mcap.
  const RecoverResult result = recover(crashed, path);
  EXPECT_EQ(result.messages, c.flushed.size());
  Reader reader;
  reader.open(path);
  EXPECT_TRUE(test::equal_messages(test::read_all(reader, {}), c.flushed));
  std::filesystem::remove_all(dir);
}

TEST(Recover, CorruptChunkInTheMiddleLosesOnlyThatChunk) {
  const auto dir = test::temp_dir("recover_corrupt");
  const std::string path = (dir / "rec.mcap").string();
  std::vector<Written> written;
  {
    Writer writer(test::options(Compression::Lz4, 4 * 1024));
    writer.open(path);
    written = test::write_recording(writer, test::spec(200, 500, true));
    writer.close();
  }
  std::vector<uint8_t> bytes = test::read_file(path);
  Reader intact;
  intact.open(path);
  const ChunkInfo victim = intact.chunks().at(2);
  std::vector<Written> expected;
  intact.for_each_message({}, [&](const MessageView& m) {
    if (m.source_offset != victim.offset) {
      expected.push_back({m.channel->id, m.sequence, m.log_time, m.publish_time, {m.data, m.data + m.size}, 0});
    }
    return true;
  });
  bytes[victim.offset + victim.length / 2] ^= 0x10;
  test::write_file(path, bytes);

  const RecoverResult result = recover(path, (dir / "fixed.mcap").string());
  ASSERT_EQ(result.damage.size(), 1u);
  EXPECT_EQ(result.damage[0].offset, victim.offset);
  Reader reader;
  reader.open((dir / "fixed.mcap").string());
  EXPECT_FALSE(reader.damage());
  EXPECT_TRUE(test::equal_messages(test::read_all(reader, {}), expected));
  std::filesystem::remove_all(dir);
}

TEST(Recover, LostSchemaKeepsItsChannelsMessagesUntyped) {
  const auto dir = test::temp_dir("recover_schema");
  const std::string path = (dir / "rec.mcap").string();
  std::vector<Written> written;
  {
    Writer writer(test::options(Compression::Zstd, 4 * 1024));
    writer.open(path);
    written = test::write_recording(writer, test::spec(90, 300, true));
    writer.close();
  }
  Reader intact;
  intact.open(path);
  const uint64_t data_end = intact.chunks().back().offset + intact.chunks().back().length;
  // Crash shape (no summary), and the first Schema record (right after the 31-byte start)
  // with a broken name length.
  std::vector<uint8_t> bytes = test::read_file(path);
  bytes.resize(data_end);
  ASSERT_EQ(bytes[31], 0x03);  // Schema opcode
  for (int k = 0; k < 4; ++k) bytes[31 + 9 + 2 + k] = 0xff;
  test::write_file(dir / "broken.mcap.tmp", bytes);

  const RecoverResult result = recover((dir / "broken.mcap.tmp").string(), path);
  EXPECT_EQ(result.messages, written.size());
  EXPECT_EQ(result.schemas, 1u);
  const bool reported = std::any_of(result.damage.begin(), result.damage.end(), [](const Damage& d) {
    return d.description.find("lost its schema 1") != std::string::npos;
  });
  EXPECT_TRUE(reported);
  Reader reader;
  reader.open(path);
  EXPECT_EQ(reader.channels().at(1).schema_id, 0);  // test/a used the lost schema
  EXPECT_EQ(reader.channels().at(2).schema_id, 2);
  EXPECT_TRUE(test::equal_messages(test::read_all(reader, {}), written));
  std::filesystem::remove_all(dir);
}

TEST(Recover, IntactFileIsCopiedWhole) {
  const auto dir = test::temp_dir("recover_intact");
  const std::string path = (dir / "rec.mcap").string();
  std::vector<Written> written;
  {
    Writer writer(test::options(Compression::Zstd, 8 * 1024));
    writer.open(path);
    written = test::write_recording(writer, test::spec(150));
    writer.close();
  }
  const RecoverResult result = recover(path, (dir / "copy.mcap").string(), test::options(Compression::None, 4 * 1024 * 1024));
  EXPECT_TRUE(result.damage.empty());
  EXPECT_EQ(result.messages, 150u);
  Reader reader;
  reader.open((dir / "copy.mcap").string());
  EXPECT_TRUE(test::equal_messages(test::read_all(reader, {}), test::in_log_time_order(written)));
  EXPECT_EQ(reader.chunks().at(0).compression, "");
  std::filesystem::remove_all(dir);
}

TEST(Recover, NotMcapIsAnInputError) {
  const auto dir = test::temp_dir("recover_foreign");
  const std::string text = "not a recording";
  test::write_file(dir / "x.mcap.tmp", std::vector<uint8_t>(text.begin(), text.end()));
  EXPECT_THROW(recover((dir / "x.mcap.tmp").string(), (dir / "x.mcap").string()), InputError);
  EXPECT_FALSE(std::filesystem::exists(dir / "x.mcap"));
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace uavmot::mcap
