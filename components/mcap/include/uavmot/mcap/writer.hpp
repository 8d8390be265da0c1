#pragma once
// Writes MCAP recordings: chunked, indexed, with a summary so readers can seek.
//
//   Writer w({.compression = Compression::Zstd});
//   w.open("flight.mcap");                       // writes flight.mcap.tmp
//   auto s = w.add_schema("uavmot::msg::TrackList", "omgidl", idl_text);
//   auto c = w.add_channel(s, "uavmot/tracks", "cdr", {{"topic", ...}, {"type", ...}});
//   w.write(c, seq, log_time_ns, publish_time_ns, payload, size);
//   w.close();                                   // summary + footer, renames to flight.mcap
//
// Durability: every chunk is written whole and flushed to the OS before write() returns, so a
// crashed recorder leaves FILE.tmp holding every complete chunk; recover() makes it valid.
// Not thread-safe: one thread writes.

#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "uavmot/mcap/types.hpp"

namespace uavmot::mcap {

struct WriterOptions {
  Compression compression = Compression::Zstd;
  int compression_level = 0;              // 0: the codec's fast default (zstd 1, lz4 fast)
  int compression_threads = 0;            // zstd only: worker threads per chunk (0: the caller's thread)
  uint64_t chunk_size = 4ull * 1024 * 1024;  // a chunk is closed once its records reach this size
  std::string profile;                    // the Header profile; "" for uavmot's own
  std::string library = "uavmot";
};

class Writer {
 public:
  explicit Writer(WriterOptions options = {});
  // Closes an open file (as close(), ignoring errors: call close() to see them).
  ~Writer();
  Writer(const Writer&) = delete;
  Writer& operator=(const Writer&) = delete;

  // Creates `path + ".tmp"`; close() renames it to `path` (replacing any file there). Throws
  // InputError if it cannot, or if the .tmp file exists (a crashed recording: never overwritten).
  void open(const std::string& path);
  // Same, with an explicit temporary name (recover() uses it when path.tmp is its input).
  void open(const std::string& path, const std::string& temporary_path);

  // Registers a schema; the same (name, encoding, data) again returns the same id.
  uint16_t add_schema(const std::string& name, const std::string& encoding, std::string_view data);
  uint16_t add_schema(const std::string& name, const std::string& encoding, const std::vector<uint8_t>& data);
  // Registers a channel on `schema_id` (0: none). Throws InvalidArgument for an unknown schema.
  uint16_t add_channel(uint16_t schema_id, const std::string& topic, const std::string& message_encoding,
                       const KeyValueMap& metadata = {});
  // Registers a schema or channel keeping its id (for copying files); throws InvalidArgument
  // if the id is taken by a different record.
  void add_schema_with_id(const Schema& schema);
  void add_channel_with_id(const Channel& channel);

  // Appends one message. Throws InvalidArgument for an unknown channel.
  void write(uint16_t channel_id, uint32_t sequence, uint64_t log_time_ns, uint64_t publish_time_ns,
             const uint8_t* data, size_t size);
  // Adds a Metadata record (e.g. the recorder's command line); indexed in the summary.
  void add_metadata(const Metadata& metadata);

  // Writes the pending chunk now (e.g. before a long pause), so a crash cannot lose it.
  void flush();
  // Writes the last chunk, DataEnd, the summary and footer, and renames the file into place.
  void close();

  bool is_open() const;
  const std::string& path() const;
  const std::string& temporary_path() const;
  // Counts so far (messages written, chunks flushed, ...).
  const Statistics& statistics() const;
  // Bytes written to the file so far, and bytes of messages not yet in a written chunk.
  uint64_t bytes_written() const;
  uint64_t pending_bytes() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace uavmot::mcap
