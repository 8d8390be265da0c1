// QueuedWriter: the recorder's writer thread keeps the queued order and accounts for every
// message, written or dropped.

#include <gtest/gtest.h>

#include <filesystem>
#include <thread>

#include "test_util.hpp"
#include "uavmot/core/error.hpp"
#include "uavmot/mcap/queued_writer.hpp"
#include "uavmot/mcap/reader.hpp"

namespace uavmot::mcap {
namespace {

using test::Written;

std::vector<Written> make_messages(size_t n, const uint16_t channels[3]) {
  std::vector<Written> v;
  for (size_t i = 0; i < n; ++i) {
    Written w;
    w.channel = channels[i % 3];
    w.sequence = static_cast<uint32_t>(i);
    w.log_time = 1000 + i * 100;
    w.publish_time = w.log_time - 1;
    w.data.assign(1000 + (i * 7919) % 30000, static_cast<uint8_t>(i * 31));
    w.data[0] = static_cast<uint8_t>(i);
    v.push_back(std::move(w));
  }
  return v;
}

TEST(QueuedWriter, EveryQueuedMessageIsWrittenInQueueOrder) {
  const auto dir = test::temp_dir("queued");
  const std::string path = (dir / "rec.mcap").string();
  QueuedWriterOptions qopts;
  qopts.max_queue_bytes = 200 * 1024;  // small: the producer has to wait for the writer thread
  QueuedWriter q(test::options(Compression::Zstd, 64 * 1024), qopts);
  q.open(path);
  const uint16_t s = q.add_schema("t::T", "omgidl", "struct T { sequence<octet> d; };");
  const uint16_t channels[3] = {q.add_channel(s, "a", "cdr"), q.add_channel(s, "b", "cdr"), q.add_channel(0, "c", "cdr")};
  const auto messages = make_messages(600, channels);
  std::thread producer([&] {
    for (const Written& w : messages) {
      EXPECT_TRUE(q.write(w.channel, w.sequence, w.log_time, w.publish_time, w.data));
    }
  });
  producer.join();
  q.close();
  EXPECT_EQ(q.dropped(), 0u);
  EXPECT_LE(q.max_queued_bytes(), qopts.max_queue_bytes + 31000);
  EXPECT_EQ(q.statistics().message_count, 600u);

  Reader reader;
  reader.open(path);
  EXPECT_FALSE(reader.damage());
  EXPECT_TRUE(test::equal_messages(test::read_all(reader, {}), messages));
  std::filesystem::remove_all(dir);
}

TEST(QueuedWriter, DroppingWhenFullAccountsForEveryMessage) {
  const auto dir = test::temp_dir("queued_drop");
  const std::string path = (dir / "rec.mcap").string();
  QueuedWriterOptions qopts;
  qopts.max_queue_bytes = 40 * 1024;
  QueuedWriter q(test::options(Compression::Zstd, 64 * 1024), qopts);
  q.open(path);
  const uint16_t channels[3] = {q.add_channel(0, "a", "cdr"), q.add_channel(0, "b", "cdr"), q.add_channel(0, "c", "cdr")};
  const auto messages = make_messages(400, channels);
  std::vector<Written> accepted;
  for (const Written& w : messages) {
    if (q.write(w.channel, w.sequence, w.log_time, w.publish_time, w.data, /*wait_when_full=*/false)) {
      accepted.push_back(w);
    }
  }
  q.close();
  EXPECT_EQ(accepted.size() + q.dropped(), messages.size());
  Reader reader;
  reader.open(path);
  EXPECT_TRUE(test::equal_messages(test::read_all(reader, {}), accepted));  // how many is up to timing
  std::filesystem::remove_all(dir);
}

TEST(QueuedWriter, UnknownChannelOrClosedWriterIsRejectedInTheCallersThread) {
  const auto dir = test::temp_dir("queued_bad");
  QueuedWriter q;
  q.open((dir / "rec.mcap").string());
  EXPECT_THROW(q.write(9, 0, 0, 0, {1, 2, 3}), InvalidArgument);
  q.close();
  EXPECT_THROW(q.write(1, 0, 0, 0, {1}), InvalidArgument);
  EXPECT_TRUE(std::filesystem::exists(dir / "rec.mcap"));
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace uavmot::mcap
