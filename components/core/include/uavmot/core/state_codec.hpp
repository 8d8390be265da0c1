#pragma once
// Little-endian byte writer and bounds-checked reader for the chain stages' saved states
// (MotionEstimator::save_state, Segmenter::save_state). Plain C++, no DDS: the formats are the libraries' own.

#include <bit>
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "uavmot/core/checksum.hpp"
#include "uavmot/core/error.hpp"

namespace uavmot::state_codec {

static_assert(sizeof(double) == 8 && sizeof(float) == 4, "IEEE 754 floats expected");
static_assert(std::endian::native == std::endian::little, "the state format is little-endian, stored as in memory");

class Writer {
 public:
  template <class T>
  void put(T value) {
    static_assert(std::is_arithmetic_v<T>);
    if constexpr (std::is_same_v<T, bool>) {
      bytes_.push_back(value ? 1 : 0);
    } else {
      // Stored little-endian, the byte order of every target this runs on (x86-64, aarch64).
      const size_t at = bytes_.size();
      bytes_.resize(at + sizeof(T));
      std::memcpy(bytes_.data() + at, &value, sizeof(T));
    }
  }
  void put_bytes(const void* data, size_t size) {
    const auto* p = static_cast<const uint8_t*>(data);
    bytes_.insert(bytes_.end(), p, p + size);
  }
  void reserve(size_t size) { bytes_.reserve(size); }
  std::vector<uint8_t>& bytes() { return bytes_; }

 private:
  std::vector<uint8_t> bytes_;
};

// Throws InputError("<what>: truncated ...") when a read runs past the end.
class Reader {
 public:
  Reader(const uint8_t* data, size_t size, std::string what) : data_(data), size_(size), what_(std::move(what)) {}

  template <class T>
  T get() {
    static_assert(std::is_arithmetic_v<T>);
    if constexpr (std::is_same_v<T, bool>) {
      const uint8_t v = get<uint8_t>();
      if (v > 1) fail("a flag is neither 0 nor 1");
      return v == 1;
    } else {
      need(sizeof(T));
      T value;
      std::memcpy(&value, data_ + pos_, sizeof(T));
      pos_ += sizeof(T);
      return value;
    }
  }
  const uint8_t* get_bytes(size_t size) {
    need(size);
    const uint8_t* p = data_ + pos_;
    pos_ += size;
    return p;
  }
  // A count of items of at least `item_bytes` each that must fit in what is left.
  uint64_t get_count(size_t item_bytes) {
    const uint64_t n = get<uint64_t>();
    if (item_bytes > 0 && n > (size_ - pos_) / item_bytes) fail("a count (" + std::to_string(n) + ") exceeds the data");
    return n;
  }
  size_t remaining() const { return size_ - pos_; }
  [[noreturn]] void fail(const std::string& why) const { throw InputError(what_ + ": " + why); }

 private:
  void need(size_t n) const {
    if (n > size_ - pos_) fail("truncated (" + std::to_string(size_) + " bytes)");
  }
  const uint8_t* data_;
  size_t size_;
  size_t pos_ = 0;
  std::string what_;
};

// A saved state's envelope, shared by the stages' formats:
//   magic (8 bytes) | u32 version | u64 payload bytes | u64 FNV-1a 64 of the payload | payload
inline constexpr size_t kEnvelopeBytes = 8 + 4 + 8 + 8;

inline std::vector<uint8_t> seal(const char (&magic)[8], uint32_t version, const std::vector<uint8_t>& payload) {
  Writer out;
  out.reserve(kEnvelopeBytes + payload.size());
  out.put_bytes(magic, sizeof magic);
  out.put(version);
  out.put(static_cast<uint64_t>(payload.size()));
  out.put(fnv1a64(payload.data(), payload.size()));
  out.put_bytes(payload.data(), payload.size());
  return std::move(out.bytes());
}

// A reader of the payload of sealed BYTES. Throws InputError ("<what>: ...") for other magic
// ("not a <noun>"), another version, a size that disagrees with the header or a checksum mismatch.
inline Reader unseal(const std::vector<uint8_t>& bytes, const char (&magic)[8], uint32_t version, const std::string& what,
                     const std::string& noun) {
  Reader header(bytes.data(), bytes.size(), what);
  if (bytes.size() < sizeof magic || std::memcmp(bytes.data(), magic, sizeof magic) != 0) {
    header.fail("not a " + noun + " (no '" + std::string(magic, sizeof magic) + "' at the start)");
  }
  header.get_bytes(sizeof magic);
  const auto found = header.get<uint32_t>();
  if (found != version) {
    header.fail("format version " + std::to_string(found) + ", this build reads version " + std::to_string(version));
  }
  const auto payload_size = header.get<uint64_t>();
  const auto checksum = header.get<uint64_t>();
  if (payload_size != header.remaining()) {
    header.fail("truncated or padded: " + std::to_string(header.remaining()) + " payload bytes, the header says " +
                std::to_string(payload_size));
  }
  const uint8_t* payload = bytes.data() + kEnvelopeBytes;
  if (fnv1a64(payload, payload_size) != checksum) header.fail("corrupt (checksum mismatch)");
  return Reader(payload, payload_size, what);
}

}  // namespace uavmot::state_codec
