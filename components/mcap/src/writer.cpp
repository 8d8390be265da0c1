#include "uavmot/mcap/writer.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <map>

#include <fmt/format.h>

#include "compression.hpp"
#include "crc32.hpp"
#include "records.hpp"
#include "uavmot/core/error.hpp"

namespace uavmot::mcap {

using detail::Opcode;

struct Writer::State {
  WriterOptions options;
  std::string path;
  std::string temporary_path;
  std::FILE* file = nullptr;
  uint64_t position = 0;       // bytes written to the file
  uint32_t data_crc = 0;       // running CRC of the data section (magic and header included)
  bool in_data_section = true;

  std::map<uint16_t, Schema> schemas;
  std::map<uint16_t, Channel> channels;
  std::vector<detail::ChunkIndexRecord> chunk_indexes;
  std::vector<detail::MetadataIndexRecord> metadata_indexes;
  Statistics statistics;

  // The open chunk: uncompressed records, per-channel (log time, offset) index, time range.
  std::vector<uint8_t> chunk;
  std::map<uint16_t, std::vector<std::pair<uint64_t, uint64_t>>> chunk_message_index;
  uint64_t chunk_start_time = 0;
  uint64_t chunk_end_time = 0;

  detail::Codec codec;
  std::vector<uint8_t> compressed;
  std::vector<uint8_t> scratch;

  void fail(const std::string& what) const {
    throw InputError(fmt::format("{}: cannot write: {} ({})", temporary_path, what, std::strerror(errno)));
  }

  void write_bytes(const void* data, size_t size) {
    if (size == 0) return;
    if (std::fwrite(data, 1, size, file) != size) fail("write failed");
    if (in_data_section) data_crc = detail::crc32_update(data_crc, data, size);
    position += size;
  }
  void write_bytes(const std::vector<uint8_t>& bytes) { write_bytes(bytes.data(), bytes.size()); }

  void sync() {
    if (std::fflush(file) != 0) fail("flush failed");
  }

  void require_open(const char* what) const {
    if (!file) throw InvalidArgument(fmt::format("mcap::Writer::{} called on a writer that is not open", what));
  }

  void flush_chunk() {
    if (chunk.empty()) return;
    detail::ChunkHeader header;
    header.message_start_time = chunk_start_time;
    header.message_end_time = chunk_end_time;
    header.uncompressed_size = chunk.size();
    header.uncompressed_crc = detail::crc32_update(0, chunk.data(), chunk.size());
    header.compression = std::string(compression_name(options.compression));
    const std::vector<uint8_t>* records = &chunk;
    if (options.compression != Compression::None) {
      try {
        codec.compress(options.compression, options.compression_level, options.compression_threads, chunk.data(),
                       chunk.size(), compressed);
      } catch (const std::runtime_error& e) {
        throw InputError(fmt::format("{}: {}", temporary_path, e.what()));
      }
      records = &compressed;
    }
    header.records_size = records->size();

    detail::ChunkIndexRecord index;
    index.message_start_time = chunk_start_time;
    index.message_end_time = chunk_end_time;
    index.chunk_start_offset = position;
    index.compression = header.compression;
    index.compressed_size = records->size();
    index.uncompressed_size = chunk.size();

    scratch.clear();
    detail::append_chunk_prefix(scratch, header);
    write_bytes(scratch);
    write_bytes(*records);
    index.chunk_length = position - index.chunk_start_offset;

    // One MessageIndex per channel, right after the chunk.
    scratch.clear();
    const uint64_t indexes_start = position;
    for (auto& [channel_id, entries] : chunk_message_index) {
      // Sorted by log time (ties by offset), so readers can bisect a channel's index.
      std::sort(entries.begin(), entries.end());
      index.message_index_offsets[channel_id] = indexes_start + scratch.size();
      detail::append_message_index(scratch, channel_id, entries);
    }
    write_bytes(scratch);
    index.message_index_length = scratch.size();
    sync();

    chunk_indexes.push_back(std::move(index));
    ++statistics.chunk_count;
    chunk.clear();
    chunk_message_index.clear();
  }

  // Schema and channel records go straight to the file, outside chunks, so that a file cut
  // after any chunk still has every definition its messages need.
  void write_definition(const std::vector<uint8_t>& record) {
    write_bytes(record);
    sync();
  }
};

Writer::Writer(WriterOptions options) : state_(std::make_unique<State>()) {
  if (options.chunk_size == 0) throw InvalidArgument("mcap::WriterOptions::chunk_size must be > 0");
  if (options.compression_threads < 0) throw InvalidArgument("mcap::WriterOptions::compression_threads must be >= 0");
  state_->options = std::move(options);
}

Writer::~Writer() {
  if (state_ && state_->file) {
    try {
      close();
    } catch (...) {
      // A destructor cannot report; the .tmp file stays and recover() can repair it.
    }
  }
}

void Writer::open(const std::string& path) { open(path, path + ".tmp"); }

void Writer::open(const std::string& path, const std::string& temporary_path) {
  if (state_->file) throw InvalidArgument("mcap::Writer::open: already open on " + state_->path);
  WriterOptions options = state_->options;
  state_ = std::make_unique<State>();
  state_->options = std::move(options);
  state_->path = path;
  state_->temporary_path = temporary_path;
  // Exclusive create: a leftover .tmp is a crashed recording that recover() can still save.
  state_->file = std::fopen(temporary_path.c_str(), "wbx");
  if (!state_->file) {
    if (errno == EEXIST) {
      throw InputError(fmt::format("{}: already exists: a previous recording did not finish; recover it (uavmot "
                                   "record --recover) or remove it",
                                   temporary_path));
    }
    state_->fail("cannot create the file");
  }
  state_->chunk.reserve(state_->options.chunk_size + 64 * 1024);

  std::vector<uint8_t> start(detail::kMagic.begin(), detail::kMagic.end());
  detail::append_header(start, Header{state_->options.profile, state_->options.library});
  state_->write_bytes(start);
  state_->sync();
}

uint16_t Writer::add_schema(const std::string& name, const std::string& encoding, std::string_view data) {
  return add_schema(name, encoding, std::vector<uint8_t>(data.begin(), data.end()));
}

uint16_t Writer::add_schema(const std::string& name, const std::string& encoding, const std::vector<uint8_t>& data) {
  state_->require_open("add_schema");
  for (const auto& [id, s] : state_->schemas) {
    if (s.name == name && s.encoding == encoding && s.data == data) return id;
  }
  Schema schema;
  schema.id = state_->schemas.empty() ? 1 : static_cast<uint16_t>(state_->schemas.rbegin()->first + 1);
  if (schema.id == 0) throw InvalidArgument("mcap::Writer: more than 65535 schemas");
  schema.name = name;
  schema.encoding = encoding;
  schema.data = data;
  add_schema_with_id(schema);
  return schema.id;
}

void Writer::add_schema_with_id(const Schema& schema) {
  state_->require_open("add_schema_with_id");
  if (schema.id == 0) throw InvalidArgument("mcap::Writer: schema id 0 is reserved");
  if (auto it = state_->schemas.find(schema.id); it != state_->schemas.end()) {
    const Schema& s = it->second;
    if (s.name == schema.name && s.encoding == schema.encoding && s.data == schema.data) return;
    throw InvalidArgument(fmt::format("mcap::Writer: schema id {} is already used by {}", schema.id, s.name));
  }
  std::vector<uint8_t> record;
  detail::append_schema(record, schema);
  state_->write_definition(record);
  state_->schemas[schema.id] = schema;
  ++state_->statistics.schema_count;
}

uint16_t Writer::add_channel(uint16_t schema_id, const std::string& topic, const std::string& message_encoding,
                             const KeyValueMap& metadata) {
  state_->require_open("add_channel");
  Channel channel;
  channel.id = state_->channels.empty() ? 1 : static_cast<uint16_t>(state_->channels.rbegin()->first + 1);
  if (channel.id == 0) throw InvalidArgument("mcap::Writer: more than 65535 channels");
  channel.schema_id = schema_id;
  channel.topic = topic;
  channel.message_encoding = message_encoding;
  channel.metadata = metadata;
  add_channel_with_id(channel);
  return channel.id;
}

void Writer::add_channel_with_id(const Channel& channel) {
  state_->require_open("add_channel_with_id");
  if (channel.schema_id != 0 && !state_->schemas.count(channel.schema_id)) {
    throw InvalidArgument(fmt::format("mcap::Writer: channel {} refers to unknown schema id {}", channel.topic,
                                      channel.schema_id));
  }
  if (auto it = state_->channels.find(channel.id); it != state_->channels.end()) {
    const Channel& c = it->second;
    if (c.schema_id == channel.schema_id && c.topic == channel.topic &&
        c.message_encoding == channel.message_encoding && c.metadata == channel.metadata) {
      return;
    }
    throw InvalidArgument(fmt::format("mcap::Writer: channel id {} is already used by {}", channel.id, c.topic));
  }
  std::vector<uint8_t> record;
  detail::append_channel(record, channel);
  state_->write_definition(record);
  state_->channels[channel.id] = channel;
  ++state_->statistics.channel_count;
}

void Writer::write(uint16_t channel_id, uint32_t sequence, uint64_t log_time_ns, uint64_t publish_time_ns,
                   const uint8_t* data, size_t size) {
  State& s = *state_;
  s.require_open("write");
  if (!s.channels.count(channel_id)) {
    throw InvalidArgument(fmt::format("mcap::Writer::write: unknown channel id {}", channel_id));
  }
  if (size > 0 && data == nullptr) throw InvalidArgument("mcap::Writer::write: null data");

  if (s.chunk.empty()) {
    s.chunk_start_time = log_time_ns;
    s.chunk_end_time = log_time_ns;
  } else {
    s.chunk_start_time = std::min(s.chunk_start_time, log_time_ns);
    s.chunk_end_time = std::max(s.chunk_end_time, log_time_ns);
  }
  s.chunk_message_index[channel_id].emplace_back(log_time_ns, s.chunk.size());
  detail::append_message_header(s.chunk, {channel_id, sequence, log_time_ns, publish_time_ns}, size);
  if (size > 0) s.chunk.insert(s.chunk.end(), data, data + size);

  Statistics& st = s.statistics;
  if (st.message_count == 0) {
    st.message_start_time = log_time_ns;
    st.message_end_time = log_time_ns;
  } else {
    st.message_start_time = std::min(st.message_start_time, log_time_ns);
    st.message_end_time = std::max(st.message_end_time, log_time_ns);
  }
  ++st.message_count;
  ++st.channel_message_counts[channel_id];

  if (s.chunk.size() >= s.options.chunk_size) s.flush_chunk();
}

void Writer::add_metadata(const Metadata& metadata) {
  state_->require_open("add_metadata");
  std::vector<uint8_t> record;
  detail::append_metadata(record, metadata);
  state_->metadata_indexes.push_back({state_->position, record.size(), metadata.name});
  state_->write_definition(record);
  ++state_->statistics.metadata_count;
}

void Writer::flush() {
  state_->require_open("flush");
  state_->flush_chunk();
}

void Writer::close() {
  State& s = *state_;
  s.require_open("close");
  s.flush_chunk();

  std::vector<uint8_t> out;
  detail::append_data_end(out, s.data_crc);
  s.write_bytes(out);
  s.in_data_section = false;

  // Summary: groups of records by opcode, then one SummaryOffset per group, then the footer.
  const uint64_t summary_start = s.position;
  out.clear();
  std::vector<detail::SummaryOffsetRecord> groups;
  auto group = [&](Opcode opcode, auto&& append_all) {
    const size_t begin = out.size();
    append_all();
    if (out.size() > begin) {
      groups.push_back({static_cast<uint8_t>(opcode), summary_start + begin, out.size() - begin});
    }
  };
  group(Opcode::Schema, [&] {
    for (const auto& [id, schema] : s.schemas) detail::append_schema(out, schema);
  });
  group(Opcode::Channel, [&] {
    for (const auto& [id, channel] : s.channels) detail::append_channel(out, channel);
  });
  group(Opcode::Statistics, [&] { detail::append_statistics(out, s.statistics); });
  group(Opcode::MetadataIndex, [&] {
    for (const auto& index : s.metadata_indexes) detail::append_metadata_index(out, index);
  });
  group(Opcode::ChunkIndex, [&] {
    for (const auto& index : s.chunk_indexes) detail::append_chunk_index(out, index);
  });
  const uint64_t summary_offset_start = summary_start + out.size();
  for (const auto& g : groups) detail::append_summary_offset(out, g);
  detail::append_footer_without_crc(out, summary_start, summary_offset_start);
  const uint32_t summary_crc = detail::crc32_update(0, out.data(), out.size());
  detail::ByteWriter(out).u32(summary_crc);
  out.insert(out.end(), detail::kMagic.begin(), detail::kMagic.end());
  s.write_bytes(out);

  std::FILE* file = s.file;
  s.file = nullptr;
  if (std::fclose(file) != 0) s.fail("close failed");
  if (std::rename(s.temporary_path.c_str(), s.path.c_str()) != 0) s.fail("cannot rename to " + s.path);
}

bool Writer::is_open() const { return state_->file != nullptr; }
const std::string& Writer::path() const { return state_->path; }
const std::string& Writer::temporary_path() const { return state_->temporary_path; }
const Statistics& Writer::statistics() const { return state_->statistics; }
uint64_t Writer::bytes_written() const { return state_->position; }
uint64_t Writer::pending_bytes() const { return state_->chunk.size(); }

}  // namespace uavmot::mcap
