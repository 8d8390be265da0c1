#pragma once
// The reader's internal state, shared by Reader (opening) and MessageCursor (iteration).

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "compression.hpp"
#include "records.hpp"
#include "source.hpp"
#include "uavmot/mcap/reader.hpp"

namespace uavmot::mcap {

namespace detail {

// Damage met while reading one chunk or record; the cursor throws it or skips it.
class DamageError : public std::runtime_error {
 public:
  explicit DamageError(Damage damage) : std::runtime_error(damage.description), damage_(std::move(damage)) {}
  const Damage& damage() const { return damage_; }

 private:
  Damage damage_;
};

// A chunk, or a message outside any chunk, with what is known of it before reading it.
struct Entry {
  enum class Kind { Chunk, Message } kind = Kind::Chunk;
  uint64_t offset = 0;
  uint64_t length = 0;  // whole record
  uint64_t start_time = 0;
  uint64_t end_time = 0;
  std::set<uint16_t> channels;  // empty: not known
  ChunkInfo info;
  std::optional<Damage> damage;  // already known to be unreadable (scan)
};

// A message found inside a decoded chunk or record.
struct FoundMessage {
  MessageHeader header;
  uint64_t position = 0;  // inside the chunk's records, for ordering ties
  size_t data_offset = 0;
  size_t data_size = 0;
};

}  // namespace detail

struct Reader::State {
  ReaderOptions options;
  std::string path;
  std::unique_ptr<detail::ByteSource> source;
  uint64_t size = 0;
  uint64_t data_start = 0;  // after the Header record
  Header header;
  std::map<uint16_t, Schema> schemas;
  std::map<uint16_t, Channel> channels;
  Statistics statistics;
  std::vector<Metadata> metadata;
  std::vector<detail::Entry> entries;
  bool indexed = false;
  std::optional<Damage> damage;       // first damage found at open
  std::optional<Damage> tail_damage;  // damage not tied to one entry (truncation, ...)
  std::vector<std::string> notes;
  detail::Codec codec;

  Damage make_damage(uint64_t offset, const std::string& what) const;
  void note_damage(const Damage& d, bool tail);

  void open_source(std::unique_ptr<detail::ByteSource> src, const std::string& name);
  void read_start();
  bool read_summary();
  void scan();
  void scan_chunk(uint64_t offset, uint64_t length, const std::vector<uint8_t>& content, uint64_t previous_end_time);
  void check_tail(uint64_t pos);

  // Reads an entry: the decoded bytes and the messages in them. Throws DamageError.
  std::shared_ptr<std::vector<uint8_t>> load(const detail::Entry& entry, std::vector<detail::FoundMessage>& found);
  // Decodes a Chunk record's content into its uncompressed records. Throws DamageError.
  std::shared_ptr<std::vector<uint8_t>> decode_chunk(uint64_t offset, const uint8_t* content, uint64_t content_size,
                                                     detail::ChunkHeader* header_out);
  // Walks the records inside a decoded chunk: registers definitions, collects messages.
  void walk_chunk_records(uint64_t chunk_offset, const std::vector<uint8_t>& records,
                          std::vector<detail::FoundMessage>& found);
  void add_schema(const Schema& schema, uint64_t offset);
  void add_channel(const Channel& channel, uint64_t offset);
};

}  // namespace uavmot::mcap
