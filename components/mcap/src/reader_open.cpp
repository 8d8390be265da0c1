// Reader::State: opening a file, through its summary or by a sequential scan.

#include <algorithm>
#include <cstring>

#include <fmt/format.h>

#include "crc32.hpp"
#include "reader_state.hpp"
#include "uavmot/core/error.hpp"

namespace uavmot::mcap {

using detail::ByteCursor;
using detail::DamageError;
using detail::Entry;
using detail::FormatError;
using detail::kMagic;
using detail::kRecordPrefixSize;
using detail::Opcode;

namespace {

uint8_t op(Opcode o) { return static_cast<uint8_t>(o); }

uint64_t read_u64(const uint8_t* p) {
  uint64_t v;
  std::memcpy(&v, p, 8);
  return v;
}

}  // namespace

Damage Reader::State::make_damage(uint64_t offset, const std::string& what) const {
  return Damage{offset, fmt::format("{}: {}", path, what)};
}

void Reader::State::note_damage(const Damage& d, bool tail) {
  if (!damage) damage = d;
  if (tail && !tail_damage) tail_damage = d;
}

void Reader::State::open_source(std::unique_ptr<detail::ByteSource> src, const std::string& name) {
  path = name;
  source = std::move(src);
  size = source->size();
  read_start();
  if (!read_summary()) {
    // Forget whatever a half-read summary left behind before scanning.
    schemas.clear();
    channels.clear();
    statistics = Statistics{};
    metadata.clear();
    entries.clear();
    scan();
    statistics.schema_count = static_cast<uint16_t>(schemas.size());
    statistics.channel_count = static_cast<uint32_t>(channels.size());
  }
}

void Reader::State::read_start() {
  if (size == 0) throw InputError(fmt::format("{}: empty file (0 bytes), not an MCAP recording", path));
  std::vector<uint8_t> bytes;
  source->read(0, std::min<uint64_t>(size, kMagic.size()), bytes);
  const bool magic_prefix = std::equal(bytes.begin(), bytes.end(), kMagic.begin());
  if (!magic_prefix) {
    throw InputError(fmt::format("{}: not an MCAP file (no MCAP magic at byte offset 0)", path));
  }
  if (size < kMagic.size() + kRecordPrefixSize) {
    throw InputError(fmt::format(
        "{}: truncated: the file ends at byte offset {} before the Header record at byte offset 8 is complete", path,
        size));
  }
  source->read(kMagic.size(), kRecordPrefixSize, bytes);
  if (bytes[0] != op(Opcode::Header)) {
    throw InputError(fmt::format("{}: not a valid MCAP file: expected a Header record at byte offset 8, found opcode "
                                 "0x{:02x}",
                                 path, bytes[0]));
  }
  const uint64_t length = read_u64(bytes.data() + 1);
  const uint64_t content_at = kMagic.size() + kRecordPrefixSize;
  if (length > size - content_at) {
    throw InputError(fmt::format("{}: truncated: the Header record at byte offset 8 needs {} bytes but the file ends "
                                 "at byte offset {}",
                                 path, content_at + length, size));
  }
  if (length > options.max_record_bytes) {
    throw InputError(fmt::format("{}: corrupt Header record at byte offset 8 (length {})", path, length));
  }
  source->read(content_at, length, bytes);
  try {
    header = detail::parse_header(ByteCursor(bytes.data(), bytes.size(), content_at));
  } catch (const FormatError& e) {
    throw InputError(fmt::format("{}: malformed Header record at byte offset 8: {} (byte offset {})", path, e.what(),
                                 e.position()));
  }
  data_start = content_at + length;
}

bool Reader::State::read_summary() {
  const uint64_t min_tail = kRecordPrefixSize + 4 + detail::kFooterRecordSize + kMagic.size();
  if (size < data_start + min_tail) return false;
  std::vector<uint8_t> tail;
  source->read(size - kMagic.size() - detail::kFooterRecordSize, detail::kFooterRecordSize + kMagic.size(), tail);
  if (!std::equal(kMagic.begin(), kMagic.end(), tail.end() - static_cast<ptrdiff_t>(kMagic.size()))) return false;
  if (tail[0] != op(Opcode::Footer) || read_u64(tail.data() + 1) != detail::kFooterContentSize) return false;
  const uint64_t footer_at = size - kMagic.size() - detail::kFooterRecordSize;
  const detail::FooterRecord footer =
      detail::parse_footer(ByteCursor(tail.data() + kRecordPrefixSize, detail::kFooterContentSize));
  if (footer.summary_start == 0) {
    notes.push_back("no summary section: read by a sequential scan");
    return false;
  }
  const uint64_t summary_end = footer.summary_offset_start != 0 ? footer.summary_offset_start : footer_at;
  if (footer.summary_start < data_start || footer.summary_start > summary_end || summary_end > footer_at) {
    notes.push_back(fmt::format("footer at byte offset {} points outside the file: read by a sequential scan",
                                footer_at));
    return false;
  }

  if (footer_at - footer.summary_start > options.max_record_bytes) {
    notes.push_back(fmt::format("summary section at byte offset {} is implausibly large: read by a sequential scan",
                                footer.summary_start));
    return false;
  }
  std::vector<uint8_t> summary;
  source->read(footer.summary_start, footer_at + kRecordPrefixSize + 16 - footer.summary_start, summary);
  if (footer.summary_crc != 0) {
    const uint32_t crc = detail::crc32_update(0, summary.data(), summary.size());
    if (crc != footer.summary_crc) {
      notes.push_back(fmt::format("summary section at byte offset {} fails its CRC: read by a sequential scan",
                                  footer.summary_start));
      return false;
    }
  }

  bool have_statistics = false;
  std::vector<detail::MetadataIndexRecord> metadata_indexes;
  try {
    ByteCursor c(summary.data(), summary_end - footer.summary_start, footer.summary_start);
    while (c.remaining() > 0) {
      const uint64_t at = c.absolute();
      const uint8_t opcode = c.u8();
      const uint64_t length = c.u64();
      ByteCursor content = c.sub(length, "summary record");
      switch (static_cast<Opcode>(opcode)) {
        case Opcode::Schema: add_schema(detail::parse_schema(content), at); break;
        case Opcode::Channel: add_channel(detail::parse_channel(content), at); break;
        case Opcode::Statistics:
          statistics = detail::parse_statistics(content);
          have_statistics = true;
          break;
        case Opcode::MetadataIndex: metadata_indexes.push_back(detail::parse_metadata_index(content)); break;
        case Opcode::ChunkIndex: {
          const detail::ChunkIndexRecord index = detail::parse_chunk_index(content);
          Entry e;
          e.kind = Entry::Kind::Chunk;
          e.offset = index.chunk_start_offset;
          e.length = index.chunk_length;
          e.start_time = index.message_start_time;
          e.end_time = index.message_end_time;
          for (const auto& [channel, offset] : index.message_index_offsets) e.channels.insert(channel);
          e.info = ChunkInfo{index.chunk_start_offset, index.chunk_length, index.message_start_time,
                             index.message_end_time, index.compression, index.compressed_size,
                             index.uncompressed_size};
          if (e.offset < data_start || e.length > footer.summary_start || e.offset > footer.summary_start - e.length) {
            throw FormatError(at, fmt::format("chunk index points to bytes {}..{}, outside the data section", e.offset,
                                              e.offset + e.length));
          }
          entries.push_back(std::move(e));
          break;
        }
        default: break;  // AttachmentIndex and future records: nothing we need
      }
    }
  } catch (const std::exception& e) {
    notes.push_back(fmt::format("summary section unusable ({}): read by a sequential scan", e.what()));
    return false;
  }
  if (!have_statistics) {
    notes.push_back("summary has no Statistics record: read by a sequential scan");
    return false;
  }
  if (statistics.message_count > 0 && entries.empty()) {
    notes.push_back("summary indexes no chunks (messages outside chunks): read by a sequential scan");
    return false;
  }
  for (const Entry& e : entries) {
    for (uint16_t channel : e.channels) {
      if (!channels.count(channel)) {
        notes.push_back(fmt::format("summary lacks channel {}: read by a sequential scan", channel));
        return false;
      }
    }
  }
  for (const auto& [id, channel] : channels) {
    if (channel.schema_id != 0 && !schemas.count(channel.schema_id)) {
      notes.push_back(fmt::format("summary lacks schema {}: read by a sequential scan", channel.schema_id));
      return false;
    }
  }
  std::sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) { return a.offset < b.offset; });

  std::vector<uint8_t> bytes;
  for (const auto& index : metadata_indexes) {
    try {
      if (index.length < kRecordPrefixSize || index.offset > size || index.length > size - index.offset ||
          index.length > options.max_record_bytes) {
        throw FormatError(index.offset, "metadata index points outside the file");
      }
      source->read(index.offset, index.length, bytes);
      if (bytes[0] != op(Opcode::Metadata)) throw FormatError(index.offset, "not a Metadata record");
      metadata.push_back(detail::parse_metadata(
          ByteCursor(bytes.data() + kRecordPrefixSize, bytes.size() - kRecordPrefixSize, index.offset)));
    } catch (const FormatError& e) {
      notes.push_back(fmt::format("metadata record at byte offset {} unreadable: {}", index.offset, e.what()));
    }
  }
  indexed = true;
  return true;
}

void Reader::State::add_schema(const Schema& schema, uint64_t offset) {
  if (schema.id == 0) throw FormatError(offset, "Schema record with the reserved id 0");
  auto [it, inserted] = schemas.emplace(schema.id, schema);
  if (!inserted && (it->second.name != schema.name || it->second.data != schema.data)) {
    throw FormatError(offset, fmt::format("Schema id {} defined twice differently", schema.id));
  }
}

void Reader::State::add_channel(const Channel& channel, uint64_t offset) {
  auto [it, inserted] = channels.emplace(channel.id, channel);
  if (!inserted && (it->second.topic != channel.topic || it->second.schema_id != channel.schema_id)) {
    throw FormatError(offset, fmt::format("Channel id {} defined twice differently", channel.id));
  }
}

void Reader::State::scan() {
  indexed = false;
  std::vector<uint8_t> bytes;
  source->read(0, data_start, bytes);
  uint32_t crc = detail::crc32_update(0, bytes.data(), bytes.size());
  uint64_t pos = data_start;
  uint64_t last_end_time = 0;
  std::vector<uint8_t> content;
  for (;;) {
    if (pos == size) {
      note_damage(make_damage(pos, fmt::format("truncated: the file ends at byte offset {} without a DataEnd record "
                                               "(the recorder did not close it; recover() makes it valid)",
                                               pos)),
                  true);
      return;
    }
    if (size - pos < kRecordPrefixSize) {
      note_damage(make_damage(pos, fmt::format("truncated: the record at byte offset {} is cut by the end of the file "
                                               "at byte offset {}",
                                               pos, size)),
                  true);
      return;
    }
    source->read(pos, kRecordPrefixSize, bytes);
    const uint8_t opcode = bytes[0];
    const uint64_t length = read_u64(bytes.data() + 1);
    const uint64_t content_at = pos + kRecordPrefixSize;
    if (length > size - content_at) {
      note_damage(make_damage(pos, fmt::format("truncated: the {} record at byte offset {} needs {} bytes but the "
                                               "file ends at byte offset {}",
                                               detail::opcode_name(opcode), pos, kRecordPrefixSize + length, size)),
                  true);
      return;
    }
    const bool needs_content = opcode == op(Opcode::Schema) || opcode == op(Opcode::Channel) ||
                               opcode == op(Opcode::Message) || opcode == op(Opcode::Chunk) ||
                               opcode == op(Opcode::Metadata) || opcode == op(Opcode::DataEnd);
    if (needs_content && length > options.max_record_bytes) {
      note_damage(make_damage(pos, fmt::format("corrupt {} record at byte offset {}: length {} exceeds the {} byte "
                                               "limit",
                                               detail::opcode_name(opcode), pos, length, options.max_record_bytes)),
                  true);
      return;
    }
    if (opcode == op(Opcode::DataEnd)) {
      source->read(content_at, length, content);
      try {
        const uint32_t stored = detail::parse_data_end(ByteCursor(content.data(), content.size(), content_at));
        if (stored != 0 && stored != crc) {
          note_damage(make_damage(pos, fmt::format("corrupt: the data section fails its CRC (DataEnd at byte offset "
                                                   "{}: stored 0x{:08x}, computed 0x{:08x})",
                                                   pos, stored, crc)),
                      true);
        }
      } catch (const FormatError& e) {
        note_damage(make_damage(pos, fmt::format("malformed DataEnd record at byte offset {}: {}", pos, e.what())),
                    true);
      }
      check_tail(content_at + length);
      return;
    }
    crc = detail::crc32_update(crc, bytes.data(), bytes.size());
    if (!needs_content) {
      // Stream the bytes through the CRC without keeping them.
      for (uint64_t done = 0; done < length;) {
        const uint64_t n = std::min<uint64_t>(length - done, 16u << 20);
        source->read(content_at + done, n, content);
        crc = detail::crc32_update(crc, content.data(), content.size());
        done += n;
      }
      if (opcode == op(Opcode::Attachment)) ++statistics.attachment_count;
      if (opcode == op(Opcode::Header) || opcode == op(Opcode::Footer)) {
        note_damage(make_damage(pos, fmt::format("corrupt: unexpected {} record at byte offset {} in the data section",
                                                 detail::opcode_name(opcode), pos)),
                    true);
        return;
      }
      pos = content_at + length;
      continue;
    }
    source->read(content_at, length, content);
    crc = detail::crc32_update(crc, content.data(), content.size());
    try {
      ByteCursor c(content.data(), content.size(), content_at);
      switch (static_cast<Opcode>(opcode)) {
        case Opcode::Schema: add_schema(detail::parse_schema(c), pos); break;
        case Opcode::Channel: add_channel(detail::parse_channel(c), pos); break;
        case Opcode::Metadata:
          metadata.push_back(detail::parse_metadata(c));
          ++statistics.metadata_count;
          break;
        case Opcode::Message: {
          const detail::MessageHeader h = detail::parse_message_header(c);
          if (!channels.count(h.channel_id)) {
            throw FormatError(pos, fmt::format("message on channel {}, which has no Channel record", h.channel_id));
          }
          Entry e;
          e.kind = Entry::Kind::Message;
          e.offset = pos;
          e.length = kRecordPrefixSize + length;
          e.start_time = e.end_time = h.log_time;
          e.channels.insert(h.channel_id);
          entries.push_back(std::move(e));
          Statistics& st = statistics;
          st.message_start_time = st.message_count == 0 ? h.log_time : std::min(st.message_start_time, h.log_time);
          st.message_end_time = st.message_count == 0 ? h.log_time : std::max(st.message_end_time, h.log_time);
          ++st.message_count;
          ++st.channel_message_counts[h.channel_id];
          last_end_time = std::max(last_end_time, h.log_time);
          break;
        }
        case Opcode::Chunk:
          scan_chunk(pos, kRecordPrefixSize + length, content, last_end_time);
          last_end_time = std::max(last_end_time, entries.back().end_time);
          break;
        default: break;
      }
    } catch (const FormatError& e) {
      note_damage(make_damage(pos, fmt::format("malformed {} record at byte offset {}: {}",
                                               detail::opcode_name(opcode), pos, e.what())),
                  true);
    }
    pos = content_at + length;
  }
}

void Reader::State::scan_chunk(uint64_t offset, uint64_t length, const std::vector<uint8_t>& content,
                               uint64_t previous_end_time) {
  Entry e;
  e.kind = Entry::Kind::Chunk;
  e.offset = offset;
  e.length = length;
  e.start_time = e.end_time = previous_end_time;  // until the header says better
  e.info.offset = offset;
  e.info.length = length;
  ++statistics.chunk_count;
  try {
    detail::ChunkHeader header;
    std::vector<detail::FoundMessage> found;
    try {
      ByteCursor c(content.data(), content.size(), offset + kRecordPrefixSize);
      header = detail::parse_chunk_header(c);
    } catch (const FormatError& err) {
      throw DamageError(make_damage(offset, fmt::format("malformed Chunk record at byte offset {}: {}", offset,
                                                        err.what())));
    }
    e.start_time = header.message_start_time;
    e.end_time = header.message_end_time;
    e.info = ChunkInfo{offset,         length, header.message_start_time, header.message_end_time, header.compression,
                       header.records_size, header.uncompressed_size};
    auto records = decode_chunk(offset, content.data(), content.size(), nullptr);
    walk_chunk_records(offset, *records, found);
    for (const auto& m : found) {
      e.channels.insert(m.header.channel_id);
      Statistics& st = statistics;
      const uint64_t t = m.header.log_time;
      st.message_start_time = st.message_count == 0 ? t : std::min(st.message_start_time, t);
      st.message_end_time = st.message_count == 0 ? t : std::max(st.message_end_time, t);
      ++st.message_count;
      ++st.channel_message_counts[m.header.channel_id];
    }
  } catch (const DamageError& err) {
    e.damage = err.damage();
    note_damage(err.damage(), false);
  }
  entries.push_back(std::move(e));
}

void Reader::State::check_tail(uint64_t pos) {
  // After DataEnd: summary records, the footer, then the closing magic.
  std::vector<uint8_t> bytes;
  for (;;) {
    if (size - pos < kRecordPrefixSize) {
      note_damage(make_damage(pos, fmt::format("truncated: the file ends at byte offset {} inside the summary section "
                                               "(every message is intact)",
                                               size)),
                  true);
      return;
    }
    source->read(pos, kRecordPrefixSize, bytes);
    const uint8_t opcode = bytes[0];
    const uint64_t length = read_u64(bytes.data() + 1);
    if (length > size - pos - kRecordPrefixSize) {
      note_damage(make_damage(pos, fmt::format("truncated: the {} record at byte offset {} in the summary section is "
                                               "cut by the end of the file at byte offset {} (every message is intact)",
                                               detail::opcode_name(opcode), pos, size)),
                  true);
      return;
    }
    pos += kRecordPrefixSize + length;
    if (opcode == op(Opcode::Footer)) break;
  }
  if (size - pos != kMagic.size()) {
    note_damage(make_damage(pos, fmt::format("{}: the footer ends at byte offset {} but the file has {} bytes, not the "
                                             "8-byte closing magic (every message is intact)",
                                             size - pos < kMagic.size() ? "truncated" : "corrupt", pos, size)),
                true);
    return;
  }
  source->read(pos, kMagic.size(), bytes);
  if (!std::equal(kMagic.begin(), kMagic.end(), bytes.begin())) {
    note_damage(make_damage(pos, fmt::format("corrupt closing magic at byte offset {} (every message is intact)", pos)),
                true);
  }
}

}  // namespace uavmot::mcap
