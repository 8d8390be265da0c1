#pragma once
// Shared helpers for the MCAP tests: deterministic recordings and what was written to them.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include <unistd.h>

#include "uavmot/core/error.hpp"
#include "uavmot/mcap/reader.hpp"
#include "uavmot/mcap/writer.hpp"

namespace uavmot::mcap::test {

struct Written {
  uint16_t channel = 0;
  uint32_t sequence = 0;
  uint64_t log_time = 0;
  uint64_t publish_time = 0;
  std::vector<uint8_t> data;
  size_t order = 0;  // write order
};

inline bool same(const Written& w, const MessageView& m) {
  return w.channel == m.channel->id && w.sequence == m.sequence && w.log_time == m.log_time &&
         w.publish_time == m.publish_time && w.data.size() == m.size &&
         std::equal(w.data.begin(), w.data.end(), m.data);
}

// Messages in the order a reader must return them: by log time, ties in write order.
inline std::vector<Written> in_log_time_order(std::vector<Written> v) {
  std::stable_sort(v.begin(), v.end(), [](const Written& a, const Written& b) { return a.log_time < b.log_time; });
  return v;
}

inline std::filesystem::path temp_dir(const std::string& name) {
  auto dir = std::filesystem::temp_directory_path() / ("uavmot_mcap_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

inline std::vector<uint8_t> read_file(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::vector<uint8_t>(std::istreambuf_iterator<char>(in), {});
}

inline void write_file(const std::filesystem::path& p, const std::vector<uint8_t>& bytes) {
  std::ofstream out(p, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

struct RecordingSpec {
  size_t messages = 300;
  size_t max_payload = 3000;
  bool monotonic = false;  // else log times jitter, so chunks overlap in time
  uint32_t seed = 7;
};

// Three channels (two share a schema) with payloads that compress partly: a counter ramp with
// random bytes sprinkled in. Writes through `writer`, which must be open.
inline std::vector<Written> write_recording(Writer& writer, const RecordingSpec& spec) {
  const uint16_t s1 = writer.add_schema("test::A", "omgidl", std::string("struct A { long x; };"));
  const uint16_t s2 = writer.add_schema("test::B", "omgidl", std::string("struct B { sequence<octet> d; };"));
  const uint16_t channels[3] = {
      writer.add_channel(s1, "test/a", "cdr", {{"topic", "test/a"}, {"type", "test::A"}}),
      writer.add_channel(s2, "test/b", "cdr", {{"topic", "test/b"}, {"reliability", "RELIABLE"}}),
      writer.add_channel(s2, "test/c", "cdr", {}),
  };
  std::mt19937 rng(spec.seed);
  std::vector<Written> written;
  for (size_t i = 0; i < spec.messages; ++i) {
    Written w;
    w.channel = channels[i % 3];
    w.sequence = static_cast<uint32_t>(i / 3);
    const int64_t jitter = spec.monotonic ? 0 : static_cast<int64_t>(rng() % 9000) - 4500;
    w.log_time = static_cast<uint64_t>(1'000'000'000 + static_cast<int64_t>(i) * 1000 + jitter);
    if (i % 50 == 7 && i > 0) w.log_time = written.back().log_time;  // equal times: ties keep write order
    w.publish_time = w.log_time - 10;
    w.data.resize(rng() % (spec.max_payload + 1));
    for (size_t k = 0; k < w.data.size(); ++k) {
      w.data[k] = (k % 16 == 0) ? static_cast<uint8_t>(rng()) : static_cast<uint8_t>(k + i);
    }
    w.order = i;
    writer.write(w.channel, w.sequence, w.log_time, w.publish_time, w.data.data(), w.data.size());
    written.push_back(std::move(w));
  }
  return written;
}

// Reads every message (OnDamage::Throw), returning them; rethrows nothing, reports the error text.
inline std::vector<Written> read_all(Reader& reader, const ReadFilter& filter, std::string* error = nullptr) {
  std::vector<Written> out;
  MessageCursor cursor = reader.messages(filter);
  MessageView m;
  try {
    while (cursor.next(m)) {
      Written w;
      w.channel = m.channel->id;
      w.sequence = m.sequence;
      w.log_time = m.log_time;
      w.publish_time = m.publish_time;
      w.data.assign(m.data, m.data + m.size);
      out.push_back(std::move(w));
    }
  } catch (const InputError& e) {
    if (!error) throw;
    *error = e.what();
  }
  return out;
}

inline WriterOptions options(Compression compression, uint64_t chunk_size) {
  WriterOptions o;
  o.compression = compression;
  o.chunk_size = chunk_size;
  return o;
}

inline RecordingSpec spec(size_t messages, size_t max_payload = 3000, bool monotonic = false) {
  RecordingSpec s;
  s.messages = messages;
  s.max_payload = max_payload;
  s.monotonic = monotonic;
  return s;
}

inline std::string compression_test_name(const ::testing::TestParamInfo<Compression>& p) {
  return p.param == Compression::None ? std::string("None") : std::string(compression_name(p.param));
}

inline bool equal_messages(const std::vector<Written>& a, const std::vector<Written>& b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i) {
    if (a[i].channel != b[i].channel || a[i].sequence != b[i].sequence || a[i].log_time != b[i].log_time ||
        a[i].publish_time != b[i].publish_time || a[i].data != b[i].data) {
      return false;
    }
  }
  return true;
}

}  // namespace uavmot::mcap::test
