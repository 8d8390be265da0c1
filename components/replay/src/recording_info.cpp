#include "uavmot/replay/recording_info.hpp"

#include <ctime>
#include <set>

#include <fmt/format.h>

namespace uavmot::replay {

std::string format_time(uint64_t ns) {
  const auto seconds = static_cast<std::time_t>(ns / 1000000000ull);
  const uint64_t fraction = ns % 1000000000ull;
  std::tm utc{};
  gmtime_r(&seconds, &utc);
  char date[64];
  std::strftime(date, sizeof(date), "%Y-%m-%d %H:%M:%S", &utc);
  return fmt::format("{}.{:09d} UTC ({}.{:09d})", date, fraction, static_cast<uint64_t>(seconds), fraction);
}

namespace {
std::string human_size(uint64_t bytes) {
  if (bytes >= (1ull << 30)) return fmt::format("{:.1f} GiB", static_cast<double>(bytes) / (1ull << 30));
  if (bytes >= (1ull << 20)) return fmt::format("{:.1f} MiB", static_cast<double>(bytes) / (1ull << 20));
  if (bytes >= 1024) return fmt::format("{:.1f} KiB", static_cast<double>(bytes) / 1024);
  return fmt::format("{} B", bytes);
}
}  // namespace

std::string recording_info(const mcap::Reader& reader) {
  const auto& stats = reader.statistics();
  std::set<std::string> compressions;
  for (const auto& chunk : reader.chunks()) compressions.insert(chunk.compression.empty() ? "none" : chunk.compression);
  std::string compression;
  for (const auto& c : compressions) compression += (compression.empty() ? "" : ", ") + c;
  if (compression.empty()) compression = "none (no chunks)";

  const uint64_t duration = stats.message_end_time - stats.message_start_time;
  std::string out;
  out += fmt::format("Files:             {}\n", reader.path());
  out += fmt::format("Bag size:          {}\n", human_size(reader.file_size()));
  out += fmt::format("Storage id:        mcap (library '{}', profile '{}')\n", reader.header().library,
                     reader.header().profile);
  out += fmt::format("Duration:          {:.3f}s\n", static_cast<double>(duration) / 1e9);
  out += fmt::format("Start:             {}\n", stats.message_count ? format_time(stats.message_start_time) : "-");
  out += fmt::format("End:               {}\n", stats.message_count ? format_time(stats.message_end_time) : "-");
  out += fmt::format("Messages:          {}\n", stats.message_count);
  out += fmt::format("Chunks:            {} ({})\n", stats.chunk_count, compression);
  out += fmt::format("Index:             {}\n", reader.indexed() ? "summary" : "none (read by a scan)");
  bool first = true;
  for (const auto& [id, channel] : reader.channels()) {
    const auto schema = reader.schemas().find(channel.schema_id);
    const std::string type = schema == reader.schemas().end() ? "-" : schema->second.name;
    const auto count = stats.channel_message_counts.find(id);
    out += fmt::format("{}Topic: {} | Type: {} | Count: {} | Serialization Format: {}\n",
                       first ? "Topic information: " : "                   ", channel.topic, type,
                       count == stats.channel_message_counts.end() ? 0 : count->second, channel.message_encoding);
    first = false;
  }
  if (first) out += "Topic information: (none)\n";
  if (reader.damage()) out += fmt::format("Damage:            {}\n", reader.damage()->description);
  for (const auto& note : reader.notes()) out += fmt::format("Note:              {}\n", note);
  return out;
}

}  // namespace uavmot::replay
