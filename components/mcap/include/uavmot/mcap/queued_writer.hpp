#pragma once
// A Writer on its own thread behind a bounded queue, for recorders: the caller (a DDS listener)
// hands over a payload and returns at once; compression and disk writes happen on the writer
// thread, so a slow chunk or a disk hiccup is absorbed by the queue instead of losing samples.
// Messages reach the file in the order they were queued, whatever the thread timing.
//
//   QueuedWriter q(WriterOptions{...}, {.max_queue_bytes = 512 << 20});
//   q.open("flight.mcap");
//   auto c = q.add_channel(q.add_schema(...), "uavmot/frames", "cdr", metadata);
//   q.write(c, seq, log_ns, pub_ns, std::vector<uint8_t>(payload, payload + n));  // blocks only when full
//   q.close();

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <exception>
#include <mutex>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "uavmot/mcap/writer.hpp"

namespace uavmot::mcap {

struct QueuedWriterOptions {
  uint64_t max_queue_bytes = 256ull << 20;  // payload bytes waiting (256 MiB: about 2 s of 60 Hz 1080p)
};

class QueuedWriter {
 public:
  explicit QueuedWriter(WriterOptions writer_options = {}, QueuedWriterOptions options = {});
  // Drains and closes (errors ignored: call close() to see them).
  ~QueuedWriter();
  QueuedWriter(const QueuedWriter&) = delete;
  QueuedWriter& operator=(const QueuedWriter&) = delete;

  void open(const std::string& path);
  uint16_t add_schema(const std::string& name, const std::string& encoding, std::string_view data);
  uint16_t add_channel(uint16_t schema_id, const std::string& topic, const std::string& message_encoding,
                       const KeyValueMap& metadata = {});
  void add_metadata(const Metadata& metadata);

  // Queues one message. When the queue is full: waits for room if `wait_when_full`, else drops
  // the message, counts it in dropped() and returns false. Throws InvalidArgument for an unknown
  // channel, and rethrows (as InputError) a failure of the writer thread.
  bool write(uint16_t channel_id, uint32_t sequence, uint64_t log_time_ns, uint64_t publish_time_ns,
             std::vector<uint8_t> data, bool wait_when_full = true);

  // Waits for the queue to drain, writes the summary and renames the file into place.
  void close();

  uint64_t dropped() const;
  uint64_t queued_bytes() const;
  uint64_t max_queued_bytes() const;  // high-water mark since open()
  Statistics statistics() const;      // of what reached the writer

 private:
  struct Item {
    uint16_t channel;
    uint32_t sequence;
    uint64_t log_time;
    uint64_t publish_time;
    std::vector<uint8_t> data;
  };
  void run();

  Writer writer_;
  QueuedWriterOptions options_;
  mutable std::mutex writer_mutex_;  // guards writer_ (definitions from the caller, messages from the thread)
  mutable std::mutex queue_mutex_;
  std::condition_variable queue_changed_;
  std::deque<Item> queue_;
  uint64_t queued_bytes_ = 0;
  uint64_t max_queued_bytes_ = 0;
  uint64_t dropped_ = 0;
  bool stopping_ = false;
  std::exception_ptr failure_;
  std::set<uint16_t> channels_;
  std::thread thread_;
};

}  // namespace uavmot::mcap
