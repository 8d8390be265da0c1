#include "records.hpp"

#include <fmt/format.h>

namespace uavmot::mcap::detail {

std::string opcode_name(uint8_t opcode) {
  static constexpr const char* kNames[] = {"?",          "Header",     "Footer",         "Schema",
                                           "Channel",    "Message",    "Chunk",          "MessageIndex",
                                           "ChunkIndex", "Attachment", "AttachmentIndex", "Statistics",
                                           "Metadata",   "MetadataIndex", "SummaryOffset", "DataEnd"};
  const char* name = opcode < std::size(kNames) && opcode != 0 ? kNames[opcode] : "unknown";
  return fmt::format("{} (0x{:02x})", name, opcode);
}

namespace {
uint8_t op(Opcode o) { return static_cast<uint8_t>(o); }
}  // namespace

void append_header(std::vector<uint8_t>& out, const Header& header) {
  ByteWriter w(out);
  const size_t at = w.begin_record(op(Opcode::Header));
  w.string(header.profile);
  w.string(header.library);
  w.end_record(at);
}

void append_schema(std::vector<uint8_t>& out, const Schema& schema) {
  ByteWriter w(out);
  const size_t at = w.begin_record(op(Opcode::Schema));
  w.u16(schema.id);
  w.string(schema.name);
  w.string(schema.encoding);
  w.u32(static_cast<uint32_t>(schema.data.size()));
  w.raw(schema.data.data(), schema.data.size());
  w.end_record(at);
}

void append_channel(std::vector<uint8_t>& out, const Channel& channel) {
  ByteWriter w(out);
  const size_t at = w.begin_record(op(Opcode::Channel));
  w.u16(channel.id);
  w.u16(channel.schema_id);
  w.string(channel.topic);
  w.string(channel.message_encoding);
  w.map(channel.metadata);
  w.end_record(at);
}

void append_message_header(std::vector<uint8_t>& out, const MessageHeader& header, uint64_t payload_size) {
  ByteWriter w(out);
  w.u8(op(Opcode::Message));
  w.u64(kMessageHeaderSize + payload_size);
  w.u16(header.channel_id);
  w.u32(header.sequence);
  w.u64(header.log_time);
  w.u64(header.publish_time);
}

void append_chunk_prefix(std::vector<uint8_t>& out, const ChunkHeader& header) {
  ByteWriter w(out);
  w.u8(op(Opcode::Chunk));
  w.u64(8 + 8 + 8 + 4 + 4 + header.compression.size() + 8 + header.records_size);
  w.u64(header.message_start_time);
  w.u64(header.message_end_time);
  w.u64(header.uncompressed_size);
  w.u32(header.uncompressed_crc);
  w.string(header.compression);
  w.u64(header.records_size);
}

void append_message_index(std::vector<uint8_t>& out, uint16_t channel_id,
                          const std::vector<std::pair<uint64_t, uint64_t>>& entries) {
  ByteWriter w(out);
  const size_t at = w.begin_record(op(Opcode::MessageIndex));
  w.u16(channel_id);
  w.u32(static_cast<uint32_t>(entries.size() * 16));
  for (const auto& [log_time, offset] : entries) {
    w.u64(log_time);
    w.u64(offset);
  }
  w.end_record(at);
}

void append_chunk_index(std::vector<uint8_t>& out, const ChunkIndexRecord& index) {
  ByteWriter w(out);
  const size_t at = w.begin_record(op(Opcode::ChunkIndex));
  w.u64(index.message_start_time);
  w.u64(index.message_end_time);
  w.u64(index.chunk_start_offset);
  w.u64(index.chunk_length);
  w.u32(static_cast<uint32_t>(index.message_index_offsets.size() * 10));
  for (const auto& [channel, offset] : index.message_index_offsets) {
    w.u16(channel);
    w.u64(offset);
  }
  w.u64(index.message_index_length);
  w.string(index.compression);
  w.u64(index.compressed_size);
  w.u64(index.uncompressed_size);
  w.end_record(at);
}

void append_statistics(std::vector<uint8_t>& out, const Statistics& s) {
  ByteWriter w(out);
  const size_t at = w.begin_record(op(Opcode::Statistics));
  w.u64(s.message_count);
  w.u16(s.schema_count);
  w.u32(s.channel_count);
  w.u32(s.attachment_count);
  w.u32(s.metadata_count);
  w.u32(s.chunk_count);
  w.u64(s.message_start_time);
  w.u64(s.message_end_time);
  w.u32(static_cast<uint32_t>(s.channel_message_counts.size() * 10));
  for (const auto& [channel, count] : s.channel_message_counts) {
    w.u16(channel);
    w.u64(count);
  }
  w.end_record(at);
}

void append_metadata(std::vector<uint8_t>& out, const Metadata& metadata) {
  ByteWriter w(out);
  const size_t at = w.begin_record(op(Opcode::Metadata));
  w.string(metadata.name);
  w.map(metadata.entries);
  w.end_record(at);
}

void append_metadata_index(std::vector<uint8_t>& out, const MetadataIndexRecord& index) {
  ByteWriter w(out);
  const size_t at = w.begin_record(op(Opcode::MetadataIndex));
  w.u64(index.offset);
  w.u64(index.length);
  w.string(index.name);
  w.end_record(at);
}

void append_summary_offset(std::vector<uint8_t>& out, const SummaryOffsetRecord& offset) {
  ByteWriter w(out);
  const size_t at = w.begin_record(op(Opcode::SummaryOffset));
  w.u8(offset.group_opcode);
  w.u64(offset.group_start);
  w.u64(offset.group_length);
  w.end_record(at);
}

void append_data_end(std::vector<uint8_t>& out, uint32_t data_section_crc) {
  ByteWriter w(out);
  const size_t at = w.begin_record(op(Opcode::DataEnd));
  w.u32(data_section_crc);
  w.end_record(at);
}

void append_footer_without_crc(std::vector<uint8_t>& out, uint64_t summary_start, uint64_t summary_offset_start) {
  ByteWriter w(out);
  w.u8(op(Opcode::Footer));
  w.u64(kFooterContentSize);
  w.u64(summary_start);
  w.u64(summary_offset_start);
}

Header parse_header(ByteCursor c) {
  Header h;
  h.profile = c.string("Header.profile");
  h.library = c.string("Header.library");
  return h;
}

Schema parse_schema(ByteCursor c) {
  Schema s;
  s.id = c.u16();
  s.name = c.string("Schema.name");
  s.encoding = c.string("Schema.encoding");
  s.data = c.bytes32("Schema.data");
  return s;
}

Channel parse_channel(ByteCursor c) {
  Channel ch;
  ch.id = c.u16();
  ch.schema_id = c.u16();
  ch.topic = c.string("Channel.topic");
  ch.message_encoding = c.string("Channel.message_encoding");
  ch.metadata = c.string_map("Channel.metadata");
  return ch;
}

MessageHeader parse_message_header(ByteCursor& c) {
  c.need(kMessageHeaderSize, "Message header");
  MessageHeader h;
  h.channel_id = c.u16();
  h.sequence = c.u32();
  h.log_time = c.u64();
  h.publish_time = c.u64();
  return h;
}

ChunkHeader parse_chunk_header(ByteCursor& c) {
  ChunkHeader h;
  h.message_start_time = c.u64();
  h.message_end_time = c.u64();
  h.uncompressed_size = c.u64();
  h.uncompressed_crc = c.u32();
  h.compression = c.string("Chunk.compression");
  h.records_size = c.u64();
  c.need(h.records_size, "Chunk.records");
  return h;
}

ChunkIndexRecord parse_chunk_index(ByteCursor c) {
  ChunkIndexRecord r;
  r.message_start_time = c.u64();
  r.message_end_time = c.u64();
  r.chunk_start_offset = c.u64();
  r.chunk_length = c.u64();
  ByteCursor offsets = c.sub(c.u32(), "ChunkIndex.message_index_offsets");
  while (offsets.remaining() > 0) {
    const uint16_t channel = offsets.u16();
    r.message_index_offsets[channel] = offsets.u64();
  }
  r.message_index_length = c.u64();
  r.compression = c.string("ChunkIndex.compression");
  r.compressed_size = c.u64();
  r.uncompressed_size = c.u64();
  return r;
}

Statistics parse_statistics(ByteCursor c) {
  Statistics s;
  s.message_count = c.u64();
  s.schema_count = c.u16();
  s.channel_count = c.u32();
  s.attachment_count = c.u32();
  s.metadata_count = c.u32();
  s.chunk_count = c.u32();
  s.message_start_time = c.u64();
  s.message_end_time = c.u64();
  ByteCursor counts = c.sub(c.u32(), "Statistics.channel_message_counts");
  while (counts.remaining() > 0) {
    const uint16_t channel = counts.u16();
    s.channel_message_counts[channel] = counts.u64();
  }
  return s;
}

Metadata parse_metadata(ByteCursor c) {
  Metadata m;
  m.name = c.string("Metadata.name");
  m.entries = c.string_map("Metadata.metadata");
  return m;
}

MetadataIndexRecord parse_metadata_index(ByteCursor c) {
  MetadataIndexRecord r;
  r.offset = c.u64();
  r.length = c.u64();
  r.name = c.string("MetadataIndex.name");
  return r;
}

FooterRecord parse_footer(ByteCursor c) {
  FooterRecord f;
  f.summary_start = c.u64();
  f.summary_offset_start = c.u64();
  f.summary_crc = c.u32();
  return f;
}

uint32_t parse_data_end(ByteCursor c) { return c.u32(); }

}  // namespace uavmot::mcap::detail
