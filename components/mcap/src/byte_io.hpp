#pragma once
// Little-endian encoding and bounds-checked decoding of MCAP's primitive types.

#include <bit>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "uavmot/mcap/types.hpp"

namespace uavmot::mcap::detail {

static_assert(std::endian::native == std::endian::little, "MCAP I/O assumes a little-endian host");

// A malformed or truncated field. `position` is an absolute byte offset when the cursor knows
// where its bytes came from (see ByteCursor::base).
class FormatError : public std::runtime_error {
 public:
  FormatError(uint64_t position, const std::string& what) : std::runtime_error(what), position_(position) {}
  uint64_t position() const { return position_; }

 private:
  uint64_t position_;
};

// Appends fields to a byte vector.
class ByteWriter {
 public:
  explicit ByteWriter(std::vector<uint8_t>& out) : out_(out) {}

  void u8(uint8_t v) { out_.push_back(v); }
  void u16(uint16_t v) { raw(&v, sizeof v); }
  void u32(uint32_t v) { raw(&v, sizeof v); }
  void u64(uint64_t v) { raw(&v, sizeof v); }
  void raw(const void* data, size_t size) {
    if (size == 0) return;
    const auto* p = static_cast<const uint8_t*>(data);
    out_.insert(out_.end(), p, p + size);
  }
  void string(std::string_view s) {
    u32(static_cast<uint32_t>(s.size()));
    raw(s.data(), s.size());
  }
  void map(const KeyValueMap& m) {
    uint32_t bytes = 0;
    for (const auto& [k, v] : m) bytes += static_cast<uint32_t>(8 + k.size() + v.size());
    u32(bytes);
    for (const auto& [k, v] : m) {
      string(k);
      string(v);
    }
  }

  // Starts a record; returns the handle end_record() needs to patch its length.
  size_t begin_record(uint8_t opcode) {
    u8(opcode);
    const size_t length_at = out_.size();
    u64(0);
    return length_at;
  }
  void end_record(size_t length_at) {
    const uint64_t length = out_.size() - length_at - 8;
    std::memcpy(out_.data() + length_at, &length, 8);
  }

  size_t size() const { return out_.size(); }

 private:
  std::vector<uint8_t>& out_;
};

// Reads fields from a byte range; every read checks the bounds and throws FormatError.
class ByteCursor {
 public:
  ByteCursor(const uint8_t* data, size_t size, uint64_t base = 0) : data_(data), size_(size), base_(base) {}

  uint8_t u8() { return fixed<uint8_t>("uint8"); }
  uint16_t u16() { return fixed<uint16_t>("uint16"); }
  uint32_t u32() { return fixed<uint32_t>("uint32"); }
  uint64_t u64() { return fixed<uint64_t>("uint64"); }

  std::string string(const char* field) {
    const uint32_t n = u32();
    need(n, field);
    std::string s(reinterpret_cast<const char*>(data_ + pos_), n);
    pos_ += n;
    return s;
  }
  // A uint32-length-prefixed byte array.
  std::vector<uint8_t> bytes32(const char* field) {
    const uint32_t n = u32();
    need(n, field);
    std::vector<uint8_t> v(data_ + pos_, data_ + pos_ + n);
    pos_ += n;
    return v;
  }
  KeyValueMap string_map(const char* field) {
    ByteCursor inner = sub(u32(), field);
    KeyValueMap m;
    while (inner.remaining() > 0) {
      std::string k = inner.string(field);
      m[k] = inner.string(field);
    }
    return m;
  }
  // A sub-range of `n` bytes, consumed from this cursor.
  ByteCursor sub(uint64_t n, const char* field) {
    need(n, field);
    ByteCursor c(data_ + pos_, static_cast<size_t>(n), base_ + pos_);
    pos_ += static_cast<size_t>(n);
    return c;
  }
  const uint8_t* take(uint64_t n, const char* field) {
    need(n, field);
    const uint8_t* p = data_ + pos_;
    pos_ += static_cast<size_t>(n);
    return p;
  }

  size_t remaining() const { return size_ - pos_; }
  size_t position() const { return pos_; }
  uint64_t absolute() const { return base_ + pos_; }

  void need(uint64_t n, const char* field) const {
    if (n > remaining()) {
      throw FormatError(absolute(), std::string(field) + " needs " + std::to_string(n) + " bytes but only " +
                                        std::to_string(remaining()) + " remain in the record");
    }
  }

 private:
  template <typename T>
  T fixed(const char* field) {
    need(sizeof(T), field);
    T v;
    std::memcpy(&v, data_ + pos_, sizeof(T));
    pos_ += sizeof(T);
    return v;
  }

  const uint8_t* data_;
  size_t size_;
  uint64_t base_;
  size_t pos_ = 0;
};

}  // namespace uavmot::mcap::detail
