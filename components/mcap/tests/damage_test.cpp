// Truncated, corrupted and foreign files: clear errors naming the byte offset, and every
// message before the damage still readable.

#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <set>

#include "test_util.hpp"
#include "uavmot/mcap/reader.hpp"
#include "uavmot/mcap/writer.hpp"

namespace uavmot::mcap {
namespace {

using test::Written;

struct Sample {
  std::vector<uint8_t> bytes;
  std::vector<Written> ordered;             // in log-time order
  std::vector<uint64_t> chunk_of;           // chunk offset of ordered[i]
  std::map<uint64_t, uint64_t> chunk_end;   // chunk offset -> end of its record
};

Sample make_sample(Compression compression, bool monotonic) {
  const auto dir = test::temp_dir("damage_sample");
  const std::string path = (dir / "rec.mcap").string();
  Sample s;
  {
    Writer writer(test::options(compression, 4 * 1024));
    writer.open(path);
    test::write_recording(writer, test::spec(240, 600, monotonic));
    writer.close();
  }
  s.bytes = test::read_file(path);
  std::filesystem::remove_all(dir);
  Reader reader;
  reader.open_memory(s.bytes);
  for (const ChunkInfo& c : reader.chunks()) s.chunk_end[c.offset] = c.offset + c.length;
  reader.for_each_message({}, [&](const MessageView& m) {
    s.ordered.push_back({m.channel->id, m.sequence, m.log_time, m.publish_time, {m.data, m.data + m.size}, 0});
    s.chunk_of.push_back(m.source_offset);
    return true;
  });
  return s;
}

bool mentions(const std::string& text, uint64_t offset) {
  return text.find(std::to_string(offset)) != std::string::npos;
}

TEST(Damage, TruncationAtAnyOffsetNamesItAndKeepsEveryCompleteChunk) {
  const Sample s = make_sample(Compression::Zstd, /*monotonic=*/false);
  ASSERT_GT(s.chunk_end.size(), 10u);
  const uint64_t size = s.bytes.size();

  std::set<uint64_t> cuts;
  for (uint64_t k = 0; k < 120; ++k) cuts.insert(k);
  for (uint64_t k = 0; k < size; k += 61) cuts.insert(k);
  for (uint64_t k = size - 150; k < size; ++k) cuts.insert(k);
  for (const auto& [offset, end] : s.chunk_end) {
    for (uint64_t k : {offset, offset + 1, offset + 9, offset + 40, end - 1, end, end + 1}) cuts.insert(k);
  }

  size_t checked = 0;
  for (uint64_t k : cuts) {
    std::vector<uint8_t> cut(s.bytes.begin(), s.bytes.begin() + static_cast<ptrdiff_t>(k));
    Reader reader;
    try {
      reader.open_memory(cut, "cut.mcap");
    } catch (const InputError& e) {
      // Only files cut inside the magic or the Header record cannot be opened at all.
      EXPECT_LT(k, 8u + 9u + 50u) << e.what();
      if (k == 0) {
        EXPECT_NE(std::string(e.what()).find("empty"), std::string::npos) << e.what();
      } else {
        EXPECT_TRUE(mentions(e.what(), k)) << "cut at " << k << ": " << e.what();
      }
      continue;
    }
    ASSERT_TRUE(reader.damage().has_value()) << "cut at " << k << " not detected";
    EXPECT_TRUE(mentions(reader.damage()->description, k)) << "cut at " << k << ": " << reader.damage()->description;
    EXPECT_FALSE(reader.indexed());

    std::vector<Written> expected;
    for (size_t i = 0; i < s.ordered.size(); ++i) {
      if (s.chunk_end.at(s.chunk_of[i]) <= k) expected.push_back(s.ordered[i]);
    }
    std::string error;
    const auto got = test::read_all(reader, {}, &error);
    EXPECT_TRUE(test::equal_messages(got, expected))
        << "cut at " << k << ": got " << got.size() << " of " << expected.size() << " messages";
    EXPECT_TRUE(mentions(error, k)) << "cut at " << k << ": iteration error '" << error << "'";
    EXPECT_EQ(reader.statistics().message_count, expected.size()) << "cut at " << k;

    ReadFilter skip;
    skip.on_damage = OnDamage::Skip;
    MessageCursor cursor = reader.messages(skip);
    MessageView m;
    size_t n = 0;
    while (cursor.next(m)) ++n;
    EXPECT_EQ(n, expected.size());
    EXPECT_EQ(cursor.skipped().size(), 1u);
    ++checked;
  }
  EXPECT_GT(checked, 300u);
}

class Corruption : public ::testing::TestWithParam<Compression> {};

TEST_P(Corruption, DamagedChunkIsReportedAtItsOffsetAndTheRestStaysReadable) {
  const Sample s = make_sample(GetParam(), /*monotonic=*/true);
  ASSERT_GT(s.chunk_end.size(), 6u);
  auto it = std::next(s.chunk_end.begin(), 3);
  const uint64_t chunk = it->first;
  std::vector<uint8_t> bytes = s.bytes;
  // A byte in the middle of the chunk's records: for lz4/zstd it breaks decompression or the
  // CRC, for an uncompressed chunk the CRC.
  const uint64_t target = (chunk + 60 + it->second) / 2;
  bytes[target] ^= 0x5a;

  std::vector<Written> before;
  std::vector<Written> others;
  for (size_t i = 0; i < s.ordered.size(); ++i) {
    if (s.chunk_of[i] < chunk) before.push_back(s.ordered[i]);
    if (s.chunk_of[i] != chunk) others.push_back(s.ordered[i]);
  }

  Reader reader;
  reader.open_memory(bytes, "corrupt.mcap");
  EXPECT_TRUE(reader.indexed());  // the summary is intact; the chunk is checked when read

  std::string error;
  const auto got = test::read_all(reader, {}, &error);
  EXPECT_TRUE(test::equal_messages(got, before)) << got.size() << " vs " << before.size();
  EXPECT_NE(error.find("corrupt.mcap"), std::string::npos) << error;
  EXPECT_TRUE(mentions(error, chunk)) << error;
  if (GetParam() == Compression::None) {
    EXPECT_NE(error.find("CRC mismatch"), std::string::npos) << error;
  }

  // Going on after the error, or skipping, yields everything else.
  ReadFilter skip;
  skip.on_damage = OnDamage::Skip;
  MessageCursor cursor = reader.messages(skip);
  std::vector<Written> rest;
  MessageView m;
  while (cursor.next(m)) {
    rest.push_back({m.channel->id, m.sequence, m.log_time, m.publish_time, {m.data, m.data + m.size}, 0});
  }
  EXPECT_TRUE(test::equal_messages(rest, others));
  ASSERT_EQ(cursor.skipped().size(), 1u);
  EXPECT_EQ(cursor.skipped()[0].offset, chunk);

  // Without the summary (a crashed recording), the scan finds it at open time.
  std::vector<uint8_t> no_summary(bytes.begin(), bytes.begin() + static_cast<ptrdiff_t>(std::prev(s.chunk_end.end())->second));
  Reader scanned;
  scanned.open_memory(no_summary, "corrupt.mcap.tmp");
  ASSERT_TRUE(scanned.damage().has_value());
  EXPECT_EQ(scanned.damage()->offset, chunk);
  EXPECT_TRUE(mentions(scanned.damage()->description, chunk)) << scanned.damage()->description;
}

INSTANTIATE_TEST_SUITE_P(Compressions, Corruption,
                         ::testing::Values(Compression::None, Compression::Lz4, Compression::Zstd),
                         test::compression_test_name);

TEST(Damage, CorruptSummaryFallsBackToAScanWithoutLosingData) {
  const Sample s = make_sample(Compression::Zstd, false);
  std::vector<uint8_t> bytes = s.bytes;
  bytes[bytes.size() - 8 - 4] ^= 0xff;  // the footer's summary CRC: the summary no longer verifies
  Reader reader;
  reader.open_memory(bytes, "summary.mcap");
  EXPECT_FALSE(reader.indexed());
  EXPECT_FALSE(reader.notes().empty());
  EXPECT_FALSE(reader.damage().has_value()) << reader.damage()->description;
  EXPECT_TRUE(test::equal_messages(test::read_all(reader, {}), s.ordered));
  EXPECT_EQ(reader.statistics().message_count, s.ordered.size());
}

TEST(Damage, DataSectionCrcIsCheckedByTheScan) {
  const Sample s = make_sample(Compression::Zstd, false);
  std::vector<uint8_t> bytes = s.bytes;
  // Corrupt a MessageIndex record (not needed to read messages) and the summary CRC, so only
  // the data-section CRC in DataEnd can tell.
  const uint64_t first_chunk_end = s.chunk_end.begin()->second;
  bytes[first_chunk_end + 9 + 2 + 4 + 3] ^= 0x01;  // a log time inside the first MessageIndex
  bytes[bytes.size() - 8 - 4] ^= 0xff;
  Reader reader;
  reader.open_memory(bytes, "crc.mcap");
  ASSERT_TRUE(reader.damage().has_value());
  EXPECT_NE(reader.damage()->description.find("CRC"), std::string::npos) << reader.damage()->description;
}

TEST(Damage, EmptyMissingAndForeignFilesAreClearErrors) {
  const auto dir = test::temp_dir("foreign");
  auto expect_error = [](const std::string& path, const std::string& needle) {
    Reader reader;
    try {
      reader.open(path);
      ADD_FAILURE() << path << ": expected InputError";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  };
  test::write_file(dir / "empty.mcap", {});
  expect_error((dir / "empty.mcap").string(), "empty file");
  const std::string text = "frame,id,bb_left\n1,1,10\n";
  test::write_file(dir / "tracks.mcap", std::vector<uint8_t>(text.begin(), text.end()));
  expect_error((dir / "tracks.mcap").string(), "not an MCAP file");
  test::write_file(dir / "short.mcap", {0x89, 'M', 'C'});
  expect_error((dir / "short.mcap").string(), "byte offset 3");
  expect_error((dir / "missing.mcap").string(), "cannot open");
  expect_error(dir.string(), "not a regular file");
  std::filesystem::remove_all(dir);
}

TEST(Damage, CorruptLengthsNeverExhaustMemory) {
  const Sample s = make_sample(Compression::Zstd, false);
  // Claim a huge uncompressed size in the first chunk's header: rejected, not allocated.
  std::vector<uint8_t> bytes = s.bytes;
  const uint64_t chunk = s.chunk_end.begin()->first;
  const uint64_t huge = 1ull << 50;
  std::memcpy(bytes.data() + chunk + 9 + 16, &huge, 8);
  Reader reader;
  reader.open_memory(bytes, "huge.mcap");
  std::string error;
  test::read_all(reader, {}, &error);
  EXPECT_TRUE(mentions(error, chunk)) << error;
}

}  // namespace
}  // namespace uavmot::mcap
