#pragma once
// SMPTE 336 KLV building blocks shared by the MISB decoders: BER lengths, BER-OID tags and the
// splitting of a byte run into KLV units. Every reader is bounds-checked: it returns nullopt (or
// skips, counting) on truncated input instead of reading past the end.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace uavmot::geo {

using Bytes = std::span<const std::uint8_t>;

// Every SMPTE universal label starts with these four bytes.
inline constexpr std::uint8_t kSmpteLabelPrefix[4] = {0x06, 0x0E, 0x2B, 0x34};
inline constexpr std::size_t kUniversalKeySize = 16;

struct BerField {
  std::uint64_t value = 0;
  std::size_t size = 0;  // bytes the field took
};

// BER short form (one byte < 0x80) or long form (0x80 | n, then n big-endian bytes, n <= 8).
// nullopt when truncated, n = 0 (indefinite) or n > 8.
std::optional<BerField> read_ber_length(Bytes bytes, std::size_t pos);
// BER-OID: 7 bits a byte, high bit set on all but the last; at most 4 bytes (tags < 2^28).
std::optional<BerField> read_ber_oid(Bytes bytes, std::size_t pos);

// One KLV unit inside a larger buffer: [offset, offset + size) holds key, length and value.
struct KlvUnit {
  std::size_t offset = 0;
  std::size_t size = 0;
  std::size_t value_offset = 0;  // from the start of the buffer
  std::size_t value_size = 0;
};

struct KlvSplit {
  std::vector<KlvUnit> units;
  std::size_t skipped_bytes = 0;  // bytes before or between units that do not start a label
  std::size_t truncated_units = 0;  // a label whose length runs past the buffer (the rest is skipped)
};

// Finds the KLV units with 16-byte SMPTE keys in `bytes`, resynchronising on the label prefix
// (so the 5-byte cell headers of metadata access units and stray bytes are skipped, counted).
KlvSplit split_klv_units(Bytes bytes);

// Big-endian unsigned integer of 1..8 bytes; the caller checks the size.
std::uint64_t read_be_unsigned(Bytes bytes);

}  // namespace uavmot::geo
