#include "uavmot/geo/klv.hpp"

#include <algorithm>

namespace uavmot::geo {

std::optional<BerField> read_ber_length(Bytes bytes, std::size_t pos) {
  if (pos >= bytes.size()) return std::nullopt;
  const std::uint8_t first = bytes[pos];
  if (first < 0x80) return BerField{first, 1};
  const std::size_t count = first & 0x7F;
  if (count == 0 || count > 8 || count > bytes.size() - pos - 1) return std::nullopt;
  return BerField{read_be_unsigned(bytes.subspan(pos + 1, count)), count + 1};
}

std::optional<BerField> read_ber_oid(Bytes bytes, std::size_t pos) {
  std::uint64_t value = 0;
  for (std::size_t i = 0; i < 4; ++i) {
    if (pos + i >= bytes.size()) return std::nullopt;
    const std::uint8_t b = bytes[pos + i];
    value = (value << 7) | (b & 0x7F);
    if ((b & 0x80) == 0) return BerField{value, i + 1};
  }
  return std::nullopt;  // longer than any tag MISB defines
}

std::uint64_t read_be_unsigned(Bytes bytes) {
  std::uint64_t value = 0;
  for (const std::uint8_t b : bytes.first(std::min<std::size_t>(bytes.size(), 8))) value = (value << 8) | b;
  return value;
}

namespace {

bool starts_label(Bytes bytes, std::size_t pos) {
  return bytes.size() - pos >= sizeof(kSmpteLabelPrefix) &&
         std::equal(std::begin(kSmpteLabelPrefix), std::end(kSmpteLabelPrefix), bytes.begin() + static_cast<std::ptrdiff_t>(pos));
}

}  // namespace

KlvSplit split_klv_units(Bytes bytes) {
  KlvSplit split;
  std::size_t pos = 0;
  while (pos < bytes.size()) {
    if (!starts_label(bytes, pos)) {
      ++split.skipped_bytes;
      ++pos;
      continue;
    }
    const auto length = bytes.size() - pos > kUniversalKeySize ? read_ber_length(bytes, pos + kUniversalKeySize) : std::nullopt;
    const std::size_t value_offset = pos + kUniversalKeySize + (length ? length->size : 0);
    if (!length || length->value > bytes.size() - value_offset) {
      // A label whose length does not fit: the rest of the buffer is that unit's, cut short (a
      // universal set's elements have labels of their own, which must not pass for packets).
      ++split.truncated_units;
      split.skipped_bytes += bytes.size() - pos;
      break;
    }
    const auto value_size = static_cast<std::size_t>(length->value);
    split.units.push_back({pos, value_offset + value_size - pos, value_offset, value_size});
    pos = value_offset + value_size;
  }
  return split;
}

}  // namespace uavmot::geo
