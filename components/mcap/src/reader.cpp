// Reader: public accessors, chunk decoding, and the log-time-ordered message cursor.

#include "uavmot/mcap/reader.hpp"

#include <algorithm>
#include <cstring>
#include <queue>

#include <fmt/format.h>

#include "crc32.hpp"
#include "reader_state.hpp"
#include "uavmot/core/error.hpp"

namespace uavmot::mcap {

using detail::ByteCursor;
using detail::DamageError;
using detail::Entry;
using detail::FormatError;
using detail::FoundMessage;
using detail::kRecordPrefixSize;
using detail::Opcode;

std::shared_ptr<std::vector<uint8_t>> Reader::State::decode_chunk(uint64_t offset, const uint8_t* content,
                                                                  uint64_t content_size,
                                                                  detail::ChunkHeader* header_out) {
  detail::ChunkHeader header;
  ByteCursor c(content, content_size, offset + kRecordPrefixSize);
  try {
    header = detail::parse_chunk_header(c);
  } catch (const FormatError& e) {
    throw DamageError(make_damage(offset, fmt::format("malformed Chunk record at byte offset {}: {}", offset, e.what())));
  }
  if (header_out) *header_out = header;
  if (header.uncompressed_size > options.max_record_bytes) {
    throw DamageError(make_damage(offset, fmt::format("corrupt Chunk record at byte offset {}: uncompressed size {} "
                                                      "exceeds the {} byte limit",
                                                      offset, header.uncompressed_size, options.max_record_bytes)));
  }
  auto records = std::make_shared<std::vector<uint8_t>>(header.uncompressed_size);
  const uint8_t* compressed = c.take(header.records_size, "Chunk.records");
  try {
    codec.decompress(header.compression, compressed, header.records_size, records->data(), records->size());
  } catch (const std::runtime_error& e) {
    throw DamageError(make_damage(offset, fmt::format("corrupt Chunk record at byte offset {}: {}", offset, e.what())));
  }
  if (header.uncompressed_crc != 0) {
    const uint32_t crc = detail::crc32_update(0, records->data(), records->size());
    if (crc != header.uncompressed_crc) {
      throw DamageError(make_damage(offset, fmt::format("corrupt Chunk record at byte offset {}: CRC mismatch (stored "
                                                        "0x{:08x}, computed 0x{:08x})",
                                                        offset, header.uncompressed_crc, crc)));
    }
  }
  return records;
}

void Reader::State::walk_chunk_records(uint64_t chunk_offset, const std::vector<uint8_t>& records,
                                       std::vector<FoundMessage>& found) {
  ByteCursor c(records.data(), records.size());
  try {
    while (c.remaining() > 0) {
      const uint64_t at = c.position();
      const uint8_t opcode = c.u8();
      const uint64_t length = c.u64();
      ByteCursor content = c.sub(length, "record inside the chunk");
      switch (static_cast<Opcode>(opcode)) {
        case Opcode::Schema: add_schema(detail::parse_schema(content), at); break;
        case Opcode::Channel: add_channel(detail::parse_channel(content), at); break;
        case Opcode::Message: {
          FoundMessage m;
          m.header = detail::parse_message_header(content);
          if (!channels.count(m.header.channel_id)) {
            throw FormatError(at, fmt::format("message on channel {}, which has no Channel record",
                                              m.header.channel_id));
          }
          m.position = at;
          m.data_offset = content.position() + (at + kRecordPrefixSize);
          m.data_size = content.remaining();
          found.push_back(m);
          break;
        }
        default: break;
      }
    }
  } catch (const FormatError& e) {
    throw DamageError(make_damage(chunk_offset, fmt::format("corrupt Chunk record at byte offset {}: {} (at byte {} of "
                                                            "its uncompressed records)",
                                                            chunk_offset, e.what(), e.position())));
  }
}

std::shared_ptr<std::vector<uint8_t>> Reader::State::load(const Entry& entry, std::vector<FoundMessage>& found) {
  if (entry.damage) throw DamageError(*entry.damage);
  const char* what = entry.kind == Entry::Kind::Chunk ? "Chunk" : "Message";
  if (entry.length < kRecordPrefixSize || entry.offset > size || entry.length > size - entry.offset) {
    throw DamageError(make_damage(entry.offset, fmt::format("the {} record indexed at byte offset {} lies outside the "
                                                            "file of {} bytes",
                                                            what, entry.offset, size)));
  }
  if (entry.length > options.max_record_bytes + kRecordPrefixSize) {
    throw DamageError(make_damage(entry.offset, fmt::format("corrupt {} record at byte offset {}: {} bytes exceed the "
                                                            "limit",
                                                            what, entry.offset, entry.length)));
  }
  auto bytes = std::make_shared<std::vector<uint8_t>>();
  source->read(entry.offset, entry.length, *bytes);
  uint64_t length;
  std::memcpy(&length, bytes->data() + 1, 8);
  const uint8_t expected = static_cast<uint8_t>(entry.kind == Entry::Kind::Chunk ? Opcode::Chunk : Opcode::Message);
  if ((*bytes)[0] != expected || length != entry.length - kRecordPrefixSize) {
    throw DamageError(make_damage(entry.offset, fmt::format("corrupt file: expected a {} record of {} bytes at byte "
                                                            "offset {}, found {} of {} bytes",
                                                            what, entry.length, entry.offset,
                                                            detail::opcode_name((*bytes)[0]), length + kRecordPrefixSize)));
  }
  if (entry.kind == Entry::Kind::Message) {
    ByteCursor c(bytes->data() + kRecordPrefixSize, length, entry.offset + kRecordPrefixSize);
    FoundMessage m;
    try {
      m.header = detail::parse_message_header(c);
    } catch (const FormatError& e) {
      throw DamageError(make_damage(entry.offset, fmt::format("malformed Message record at byte offset {}: {}",
                                                              entry.offset, e.what())));
    }
    m.data_offset = kRecordPrefixSize + c.position();
    m.data_size = c.remaining();
    found.push_back(m);
    return bytes;
  }
  auto records = decode_chunk(entry.offset, bytes->data() + kRecordPrefixSize, length, nullptr);
  walk_chunk_records(entry.offset, *records, found);
  return records;
}

// ---------------------------------------------------------------------------------------------
// MessageCursor: merges chunks by log time. Chunks are opened in order of their start time and
// only when the earliest pending message is not earlier than the next chunk's start, so
// overlapping chunks interleave correctly while at most the overlapping ones are in memory.

struct MessageCursor::Impl {
  struct Pending {
    uint64_t log_time;
    uint64_t source_offset;
    uint64_t position;
    FoundMessage message;
    std::shared_ptr<std::vector<uint8_t>> bytes;
  };
  struct Later {
    bool operator()(const Pending& a, const Pending& b) const {
      if (a.log_time != b.log_time) return a.log_time > b.log_time;
      if (a.source_offset != b.source_offset) return a.source_offset > b.source_offset;
      return a.position > b.position;
    }
  };

  Reader::State* reader = nullptr;
  ReadFilter filter;
  bool all_channels = true;
  std::set<uint16_t> wanted;
  std::vector<const Entry*> candidates;
  size_t next_candidate = 0;
  std::priority_queue<Pending, std::vector<Pending>, Later> pending;
  std::shared_ptr<std::vector<uint8_t>> current;
  std::vector<Damage> skipped;
  uint64_t chunks_loaded = 0;
  bool finished = false;

  bool wants(uint16_t channel) const { return all_channels || wanted.count(channel) > 0; }

  void damage(const Damage& d) {
    if (filter.on_damage == OnDamage::Throw) throw InputError(d.description);
    skipped.push_back(d);
  }

  void load(const Entry& entry) {
    std::vector<FoundMessage> found;
    std::shared_ptr<std::vector<uint8_t>> bytes;
    try {
      if (entry.kind == Entry::Kind::Chunk) ++chunks_loaded;
      bytes = reader->load(entry, found);
    } catch (const DamageError& e) {
      damage(e.damage());
      return;
    }
    for (const FoundMessage& m : found) {
      const uint64_t t = m.header.log_time;
      if (!wants(m.header.channel_id) || t < filter.start_time || t >= filter.end_time) continue;
      pending.push(Pending{t, entry.offset, m.position, m, bytes});
    }
  }
};

MessageCursor::MessageCursor(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
MessageCursor::MessageCursor(MessageCursor&&) noexcept = default;
MessageCursor& MessageCursor::operator=(MessageCursor&&) noexcept = default;
MessageCursor::~MessageCursor() = default;

bool MessageCursor::next(MessageView& out) {
  Impl& s = *impl_;
  for (;;) {
    while (s.next_candidate < s.candidates.size() &&
           (s.pending.empty() || s.candidates[s.next_candidate]->start_time <= s.pending.top().log_time)) {
      s.load(*s.candidates[s.next_candidate++]);  // advance first: after a throw, next() goes on
    }
    if (!s.pending.empty()) break;
    if (!s.finished) {
      s.finished = true;
      if (s.reader->tail_damage) s.damage(*s.reader->tail_damage);
    }
    return false;
  }
  Impl::Pending p = s.pending.top();
  s.pending.pop();
  s.current = p.bytes;
  const Channel& channel = s.reader->channels.at(p.message.header.channel_id);
  out.channel = &channel;
  auto schema = s.reader->schemas.find(channel.schema_id);
  out.schema = schema == s.reader->schemas.end() ? nullptr : &schema->second;
  out.sequence = p.message.header.sequence;
  out.log_time = p.message.header.log_time;
  out.publish_time = p.message.header.publish_time;
  out.data = p.bytes->data() + p.message.data_offset;
  out.size = p.message.data_size;
  out.source_offset = p.source_offset;
  out.keep_alive = p.bytes;
  return true;
}

const std::vector<Damage>& MessageCursor::skipped() const { return impl_->skipped; }
uint64_t MessageCursor::chunks_loaded() const { return impl_->chunks_loaded; }

// ---------------------------------------------------------------------------------------------

Reader::Reader(ReaderOptions options) : state_(std::make_unique<State>()) { state_->options = options; }
Reader::~Reader() = default;

void Reader::open(const std::string& path) {
  const ReaderOptions options = state_->options;
  state_ = std::make_unique<State>();
  state_->options = options;
  state_->open_source(detail::open_file_source(path), path);
}

void Reader::open_memory(std::vector<uint8_t> bytes, const std::string& name) {
  const ReaderOptions options = state_->options;
  state_ = std::make_unique<State>();
  state_->options = options;
  state_->open_source(detail::memory_source(std::move(bytes)), name);
}

const std::string& Reader::path() const { return state_->path; }
uint64_t Reader::file_size() const { return state_->size; }
const Header& Reader::header() const { return state_->header; }
const std::map<uint16_t, Schema>& Reader::schemas() const { return state_->schemas; }
const std::map<uint16_t, Channel>& Reader::channels() const { return state_->channels; }
const Statistics& Reader::statistics() const { return state_->statistics; }
const std::vector<Metadata>& Reader::metadata() const { return state_->metadata; }
bool Reader::indexed() const { return state_->indexed; }
const std::optional<Damage>& Reader::damage() const { return state_->damage; }
const std::vector<std::string>& Reader::notes() const { return state_->notes; }

std::vector<ChunkInfo> Reader::chunks() const {
  std::vector<ChunkInfo> out;
  for (const Entry& e : state_->entries) {
    if (e.kind == Entry::Kind::Chunk) out.push_back(e.info);
  }
  return out;
}

MessageCursor Reader::messages(const ReadFilter& filter) {
  if (!state_->source) throw InvalidArgument("mcap::Reader::messages called before open()");
  auto impl = std::make_unique<MessageCursor::Impl>();
  impl->reader = state_.get();
  impl->filter = filter;
  impl->all_channels = filter.topics.empty();
  for (const auto& [id, channel] : state_->channels) {
    if (filter.topics.count(channel.topic)) impl->wanted.insert(id);
  }
  for (const Entry& e : state_->entries) {
    if (e.end_time < filter.start_time || e.start_time >= filter.end_time) continue;
    if (!impl->all_channels && !e.channels.empty() && !e.damage) {
      const bool any = std::any_of(e.channels.begin(), e.channels.end(), [&](uint16_t c) { return impl->wants(c); });
      if (!any) continue;
    }
    impl->candidates.push_back(&e);
  }
  std::stable_sort(impl->candidates.begin(), impl->candidates.end(), [](const Entry* a, const Entry* b) {
    return a->start_time != b->start_time ? a->start_time < b->start_time : a->offset < b->offset;
  });
  return MessageCursor(std::move(impl));
}

uint64_t Reader::for_each_message(const ReadFilter& filter, const std::function<bool(const MessageView&)>& fn) {
  MessageCursor cursor = messages(filter);
  MessageView m;
  uint64_t n = 0;
  while (cursor.next(m)) {
    ++n;
    if (!fn(m)) break;
  }
  return n;
}

}  // namespace uavmot::mcap
