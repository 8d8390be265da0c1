#include "uavmot/mcap/recover.hpp"

#include <algorithm>
#include <cstdio>

#include "uavmot/mcap/reader.hpp"

namespace uavmot::mcap {

RecoverResult recover(const std::string& damaged_path, const std::string& out_path,
                      const std::optional<WriterOptions>& options) {
  Reader reader;
  reader.open(damaged_path);

  WriterOptions writer_options;
  if (options) {
    writer_options = *options;
  } else {
    writer_options.profile = reader.header().profile;
    writer_options.library = reader.header().library;
    const auto chunks = reader.chunks();
    writer_options.compression = chunks.empty() ? Compression::Zstd : parse_compression(chunks.front().compression);
  }

  RecoverResult result;
  if (reader.damage()) result.damage.push_back(*reader.damage());

  Writer writer(writer_options);
  // Never write over the input while reading it, even when the input is out_path.tmp.
  std::remove((out_path + ".recovering").c_str());  // left by an interrupted recover(): ours to replace
  writer.open(out_path, out_path + ".recovering");
  for (const auto& [id, schema] : reader.schemas()) writer.add_schema_with_id(schema);
  for (const auto& [id, channel] : reader.channels()) {
    Channel copy = channel;
    if (copy.schema_id != 0 && !reader.schemas().count(copy.schema_id)) {
      copy.schema_id = 0;  // its Schema record was lost; keep the messages, untyped
      result.damage.push_back({0, reader.path() + ": channel " + copy.topic + " lost its schema " +
                                      std::to_string(channel.schema_id) + "; recovered without it"});
    }
    writer.add_channel_with_id(copy);
  }
  for (const auto& metadata : reader.metadata()) writer.add_metadata(metadata);
  result.schemas = static_cast<uint32_t>(reader.schemas().size());
  result.channels = static_cast<uint32_t>(reader.channels().size());

  ReadFilter filter;
  filter.on_damage = OnDamage::Skip;
  MessageCursor cursor = reader.messages(filter);
  MessageView m;
  while (cursor.next(m)) {
    writer.write(m.channel->id, m.sequence, m.log_time, m.publish_time, m.data, m.size);
    ++result.messages;
  }
  for (const Damage& d : cursor.skipped()) {
    const bool known = std::any_of(result.damage.begin(), result.damage.end(),
                                   [&](const Damage& e) { return e.offset == d.offset; });
    if (!known) result.damage.push_back(d);
  }
  writer.close();
  return result;
}

}  // namespace uavmot::mcap
