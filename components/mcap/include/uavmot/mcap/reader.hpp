#pragma once
// Reads MCAP recordings, ours or any other writer's.
//
// open() uses the summary section (schemas, channels, statistics, chunk indexes) when the
// footer points to a valid one; otherwise it scans the file record by record, which is what a
// crashed recording (no summary) or a damaged file needs. Damage never hides the good part:
// the first problem is reported by damage() with its byte offset, every message before it
// stays readable, and iteration stops with uavmot::InputError naming the offset where the
// damage is reached (or, with OnDamage::Skip, steps over it and lists it in skipped()).
//
//   Reader r;
//   r.open("flight.mcap");
//   for (auto& [id, ch] : r.channels()) ...;
//   auto cursor = r.messages({.topics = {"uavmot/tracks"}});
//   MessageView m;
//   while (cursor.next(m)) use(m.channel->topic, m.log_time, m.data, m.size);

#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "uavmot/mcap/types.hpp"

namespace uavmot::mcap {

struct ReaderOptions {
  // A chunk or message that claims more bytes than this is treated as damage, so a corrupt
  // length cannot exhaust memory.
  uint64_t max_record_bytes = 1ull << 30;
};

enum class OnDamage {
  Throw,  // InputError when iteration reaches the damage (default)
  Skip,   // step over damaged chunks, list them in MessageCursor::skipped()
};

struct ReadFilter {
  std::set<std::string> topics;  // empty: every topic
  uint64_t start_time = 0;       // log time in ns, inclusive
  uint64_t end_time = std::numeric_limits<uint64_t>::max();  // log time in ns, exclusive
  OnDamage on_damage = OnDamage::Throw;
};

// One message. `data` stays valid until the cursor's next call to next(), or as long as a copy
// of `keep_alive` is held.
struct MessageView {
  const Channel* channel = nullptr;
  const Schema* schema = nullptr;  // null when the channel has no schema
  uint32_t sequence = 0;
  uint64_t log_time = 0;
  uint64_t publish_time = 0;
  const uint8_t* data = nullptr;
  size_t size = 0;
  uint64_t source_offset = 0;  // file offset of the chunk (or Message record) holding it
  std::shared_ptr<const void> keep_alive;
};

class Reader;

// Messages in log-time order (ties in file order). Obtained from Reader::messages(); the
// Reader must outlive it.
class MessageCursor {
 public:
  MessageCursor(MessageCursor&&) noexcept;
  MessageCursor& operator=(MessageCursor&&) noexcept;
  ~MessageCursor();

  // False at the end. Throws InputError at damage (OnDamage::Throw); calling next() again
  // after such an error continues past the damage.
  bool next(MessageView& out);
  // Damage stepped over (OnDamage::Skip), in the order met.
  const std::vector<Damage>& skipped() const;
  // How many chunks were read and decompressed so far (shows what an index saved).
  uint64_t chunks_loaded() const;

 private:
  friend class Reader;
  struct Impl;
  explicit MessageCursor(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

class Reader {
 public:
  explicit Reader(ReaderOptions options = {});
  ~Reader();
  Reader(const Reader&) = delete;
  Reader& operator=(const Reader&) = delete;

  // Throws InputError if the file cannot be opened, is empty, is not MCAP (bad magic) or its
  // Header record is unreadable. Any later damage is reported by damage(), not thrown.
  void open(const std::string& path);
  // The same on bytes in memory; `name` stands for the path in messages.
  void open_memory(std::vector<uint8_t> bytes, const std::string& name = "<memory>");

  const std::string& path() const;
  uint64_t file_size() const;
  const Header& header() const;
  const std::map<uint16_t, Schema>& schemas() const;
  const std::map<uint16_t, Channel>& channels() const;
  const Statistics& statistics() const;
  const std::vector<Metadata>& metadata() const;
  // Every chunk known from the index or the scan, in file order (damaged ones included).
  std::vector<ChunkInfo> chunks() const;
  // True when the summary section was used; false after a sequential scan.
  bool indexed() const;
  // The first damage found while opening (a scan finds truncation and corrupt chunks; with a
  // valid summary, chunks are checked only when read).
  const std::optional<Damage>& damage() const;
  // Findings that lose no data, e.g. "summary unusable, file read by a scan".
  const std::vector<std::string>& notes() const;

  MessageCursor messages(const ReadFilter& filter = {});
  // Calls `fn` for each message until it returns false; returns how many it saw.
  uint64_t for_each_message(const ReadFilter& filter, const std::function<bool(const MessageView&)>& fn);

 private:
  friend class MessageCursor;
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace uavmot::mcap
