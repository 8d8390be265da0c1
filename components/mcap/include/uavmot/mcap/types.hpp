#pragma once
// The records of an MCAP file that users of the reader and writer see (spec: mcap.dev/spec).

#include <cstdint>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace uavmot::mcap {

// How chunks are compressed. Lz4 is the LZ4 *frame* format and Zstd a zstd frame, as the spec says.
enum class Compression { None, Lz4, Zstd };

// The spec's name for a compression: "", "lz4" or "zstd".
std::string_view compression_name(Compression compression);
// "none" or "" -> None, "lz4", "zstd"; anything else throws uavmot::InputError.
Compression parse_compression(std::string_view name);

using KeyValueMap = std::map<std::string, std::string>;

struct Header {
  std::string profile;
  std::string library;
};

// A message type: for uavmot, encoding "omgidl" and the IDL text as data.
struct Schema {
  uint16_t id = 0;  // 0 is reserved for "no schema"
  std::string name;
  std::string encoding;
  std::vector<uint8_t> data;
};

// A topic: for uavmot, message encoding "cdr" and metadata with topic, type and QoS.
struct Channel {
  uint16_t id = 0;
  uint16_t schema_id = 0;  // 0: no schema
  std::string topic;
  std::string message_encoding;
  KeyValueMap metadata;
};

struct Metadata {
  std::string name;
  KeyValueMap entries;
};

struct Statistics {
  uint64_t message_count = 0;
  uint16_t schema_count = 0;
  uint32_t channel_count = 0;
  uint32_t attachment_count = 0;
  uint32_t metadata_count = 0;
  uint32_t chunk_count = 0;
  uint64_t message_start_time = 0;  // log time of the earliest message, ns (0 when there is none)
  uint64_t message_end_time = 0;    // log time of the latest message, ns
  std::map<uint16_t, uint64_t> channel_message_counts;
};

// Where a file stops being readable, and why. `description` is a complete sentence for the
// user that names the file and the byte offset.
struct Damage {
  uint64_t offset = 0;
  std::string description;
};

// One chunk (or one message outside any chunk) as the reader knows it from the index or a scan.
struct ChunkInfo {
  uint64_t offset = 0;  // of the Chunk record in the file
  uint64_t length = 0;  // of the whole record, opcode and length prefix included
  uint64_t message_start_time = 0;
  uint64_t message_end_time = 0;
  std::string compression;
  uint64_t compressed_size = 0;
  uint64_t uncompressed_size = 0;
};

}  // namespace uavmot::mcap
