// Prints what an MCAP file holds, as text (like `ros2 bag info`) or JSON; with --messages the
// JSON lists every message (topic, sequence, times, size, FNV-1a 64 of the payload), which the
// interop check (tests/mcap_js) compares with what the official TypeScript writer wrote.
//
//   mcap_info [--json] [--messages] FILE
// Exit status: 0 intact, 1 damaged (all readable messages still listed), 2 usage or unreadable.

#include <cstdio>
#include <string>

#include <nlohmann/json.hpp>

#include "uavmot/core/checksum.hpp"
#include "uavmot/core/error.hpp"
#include "uavmot/mcap/reader.hpp"

int main(int argc, char** argv) {
  using namespace uavmot::mcap;
  bool as_json = false;
  bool list_messages = false;
  std::string path;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--json") as_json = true;
    else if (a == "--messages") list_messages = true;
    else path = a;
  }
  if (path.empty()) {
    std::fprintf(stderr, "usage: mcap_info [--json] [--messages] FILE\n");
    return 2;
  }
  try {
    Reader reader;
    reader.open(path);
    nlohmann::json out;
    out["path"] = path;
    out["profile"] = reader.header().profile;
    out["library"] = reader.header().library;
    out["indexed"] = reader.indexed();
    out["notes"] = reader.notes();
    const Statistics& st = reader.statistics();
    out["messages"] = st.message_count;
    out["chunks"] = st.chunk_count;
    out["start_ns"] = st.message_start_time;
    out["end_ns"] = st.message_end_time;
    for (const auto& [id, s] : reader.schemas()) {
      out["schemas"].push_back({{"id", id}, {"name", s.name}, {"encoding", s.encoding}, {"bytes", s.data.size()}});
    }
    for (const auto& [id, c] : reader.channels()) {
      const auto count = st.channel_message_counts.find(id);
      auto schema = reader.schemas().find(c.schema_id);
      out["channels"].push_back({{"id", id},
                                 {"topic", c.topic},
                                 {"type", schema == reader.schemas().end() ? "" : schema->second.name},
                                 {"message_encoding", c.message_encoding},
                                 {"count", count == st.channel_message_counts.end() ? 0 : count->second},
                                 {"metadata", c.metadata}});
    }
    ReadFilter filter;
    filter.on_damage = OnDamage::Skip;
    MessageCursor cursor = reader.messages(filter);
    MessageView m;
    uint64_t read = 0;
    while (cursor.next(m)) {
      ++read;
      if (list_messages) {
        out["message_list"].push_back({{"topic", m.channel->topic},
                                       {"sequence", m.sequence},
                                       {"log_time", std::to_string(m.log_time)},
                                       {"publish_time", std::to_string(m.publish_time)},
                                       {"size", m.size},
                                       {"fnv1a64", std::to_string(uavmot::fnv1a64(m.data, m.size))}});
      }
    }
    out["messages_read"] = read;
    nlohmann::json damage = nlohmann::json::array();
    if (reader.damage()) damage.push_back(reader.damage()->description);
    for (const Damage& d : cursor.skipped()) {
      if (!reader.damage() || d.description != reader.damage()->description) damage.push_back(d.description);
    }
    out["damage"] = damage;

    if (as_json) {
      std::printf("%s\n", out.dump(2).c_str());
    } else {
      std::printf("File:      %s (%llu bytes, %s)\n", path.c_str(), static_cast<unsigned long long>(reader.file_size()),
                  reader.indexed() ? "indexed" : "scanned");
      std::printf("Library:   %s\n", reader.header().library.c_str());
      std::printf("Messages:  %llu in %u chunks\n", static_cast<unsigned long long>(st.message_count), st.chunk_count);
      std::printf("Duration:  %.3f s\n", st.message_count ? (st.message_end_time - st.message_start_time) * 1e-9 : 0.0);
      std::printf("Topics:\n");
      for (const auto& c : out["channels"]) {
        std::printf("  %-28s %-34s %8llu msgs  %s\n", c["topic"].get<std::string>().c_str(),
                    c["type"].get<std::string>().c_str(), c["count"].get<unsigned long long>(),
                    c["message_encoding"].get<std::string>().c_str());
      }
      for (const auto& d : damage) std::printf("DAMAGE: %s\n", d.get<std::string>().c_str());
      for (const auto& n : reader.notes()) std::printf("note: %s\n", n.c_str());
    }
    return damage.empty() ? 0 : 1;
  } catch (const uavmot::InputError& e) {
    std::fprintf(stderr, "mcap_info: %s\n", e.what());
    return 2;
  }
}
