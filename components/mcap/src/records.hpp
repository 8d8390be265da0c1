#pragma once
// MCAP record layouts (spec mcap.dev/spec, version 0): opcodes, encoders and decoders.
// Every record is <opcode u8><content length u64><content>, little-endian.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "byte_io.hpp"
#include "uavmot/mcap/types.hpp"

namespace uavmot::mcap::detail {

constexpr std::array<uint8_t, 8> kMagic = {0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n'};
constexpr uint64_t kRecordPrefixSize = 1 + 8;
constexpr uint64_t kFooterContentSize = 8 + 8 + 4;
constexpr uint64_t kFooterRecordSize = kRecordPrefixSize + kFooterContentSize;

enum class Opcode : uint8_t {
  Header = 0x01,
  Footer = 0x02,
  Schema = 0x03,
  Channel = 0x04,
  Message = 0x05,
  Chunk = 0x06,
  MessageIndex = 0x07,
  ChunkIndex = 0x08,
  Attachment = 0x09,
  AttachmentIndex = 0x0A,
  Statistics = 0x0B,
  Metadata = 0x0C,
  MetadataIndex = 0x0D,
  SummaryOffset = 0x0E,
  DataEnd = 0x0F,
};

// "Chunk (0x06)" for messages.
std::string opcode_name(uint8_t opcode);

// Fixed part of a Message record, before its payload.
constexpr uint64_t kMessageHeaderSize = 2 + 4 + 8 + 8;

struct MessageHeader {
  uint16_t channel_id = 0;
  uint32_t sequence = 0;
  uint64_t log_time = 0;
  uint64_t publish_time = 0;
};

// The fields of a Chunk record before its (compressed) records.
struct ChunkHeader {
  uint64_t message_start_time = 0;
  uint64_t message_end_time = 0;
  uint64_t uncompressed_size = 0;
  uint32_t uncompressed_crc = 0;
  std::string compression;
  uint64_t records_size = 0;
};

struct ChunkIndexRecord {
  uint64_t message_start_time = 0;
  uint64_t message_end_time = 0;
  uint64_t chunk_start_offset = 0;
  uint64_t chunk_length = 0;
  std::map<uint16_t, uint64_t> message_index_offsets;
  uint64_t message_index_length = 0;
  std::string compression;
  uint64_t compressed_size = 0;
  uint64_t uncompressed_size = 0;
};

struct MetadataIndexRecord {
  uint64_t offset = 0;
  uint64_t length = 0;
  std::string name;
};

struct SummaryOffsetRecord {
  uint8_t group_opcode = 0;
  uint64_t group_start = 0;
  uint64_t group_length = 0;
};

struct FooterRecord {
  uint64_t summary_start = 0;
  uint64_t summary_offset_start = 0;
  uint32_t summary_crc = 0;
};

// Encoders append a whole record (prefix included) to `out`.
void append_header(std::vector<uint8_t>& out, const Header& header);
void append_schema(std::vector<uint8_t>& out, const Schema& schema);
void append_channel(std::vector<uint8_t>& out, const Channel& channel);
void append_message_header(std::vector<uint8_t>& out, const MessageHeader& header, uint64_t payload_size);
// The chunk record up to its records bytes, which the caller writes next (`header.records_size` of them).
void append_chunk_prefix(std::vector<uint8_t>& out, const ChunkHeader& header);
void append_message_index(std::vector<uint8_t>& out, uint16_t channel_id,
                          const std::vector<std::pair<uint64_t, uint64_t>>& entries);
void append_chunk_index(std::vector<uint8_t>& out, const ChunkIndexRecord& index);
void append_statistics(std::vector<uint8_t>& out, const Statistics& statistics);
void append_metadata(std::vector<uint8_t>& out, const Metadata& metadata);
void append_metadata_index(std::vector<uint8_t>& out, const MetadataIndexRecord& index);
void append_summary_offset(std::vector<uint8_t>& out, const SummaryOffsetRecord& offset);
void append_data_end(std::vector<uint8_t>& out, uint32_t data_section_crc);
// The footer without its CRC (the CRC covers these bytes too); append the CRC with ByteWriter::u32.
void append_footer_without_crc(std::vector<uint8_t>& out, uint64_t summary_start, uint64_t summary_offset_start);

// Decoders read a record's content (the bytes after the length prefix). They ignore trailing
// fields, as the spec asks readers to do, and throw FormatError on short content.
Header parse_header(ByteCursor content);
Schema parse_schema(ByteCursor content);
Channel parse_channel(ByteCursor content);
MessageHeader parse_message_header(ByteCursor& content);  // leaves `content` at the payload
ChunkHeader parse_chunk_header(ByteCursor& content);      // leaves `content` at the records
ChunkIndexRecord parse_chunk_index(ByteCursor content);
Statistics parse_statistics(ByteCursor content);
Metadata parse_metadata(ByteCursor content);
MetadataIndexRecord parse_metadata_index(ByteCursor content);
FooterRecord parse_footer(ByteCursor content);
uint32_t parse_data_end(ByteCursor content);

}  // namespace uavmot::mcap::detail
