#include "uavmot/geo/misb0601.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "uavmot/core/error.hpp"

namespace uavmot::geo {

namespace {

// One ST 0601 linear mapping: an n-byte integer onto [min, max]. Signed values are symmetric,
// v * (max - min) / (2^(8n) - 2), with the most negative integer meaning "error"; unsigned ones
// are min + v * (max - min) / (2^(8n) - 1).
struct LinearMapping {
  std::size_t size;
  bool is_signed;
  double min;
  double max;
};

std::optional<double>* field_for(UasMetadata& m, std::uint64_t tag) {
  switch (tag) {
    case 5: return &m.platform_heading_deg;
    case 6: return &m.platform_pitch_deg;
    case 7: return &m.platform_roll_deg;
    case 13: return &m.sensor_latitude_deg;
    case 14: return &m.sensor_longitude_deg;
    case 15: return &m.sensor_true_altitude_m;
    case 16: return &m.sensor_hfov_deg;
    case 17: return &m.sensor_vfov_deg;
    case 18: return &m.sensor_relative_azimuth_deg;
    case 19: return &m.sensor_relative_elevation_deg;
    case 20: return &m.sensor_relative_roll_deg;
    case 21: return &m.slant_range_m;
    case 22: return &m.target_width_m;
    case 23: return &m.frame_center_latitude_deg;
    case 24: return &m.frame_center_longitude_deg;
    case 25: return &m.frame_center_elevation_m;
    default: break;
  }
  if (tag >= 26 && tag <= 33) {  // offset corners: lat 1, lon 1, lat 2, lon 2, ...
    const std::size_t point = (tag - 26) / 2;
    return (tag - 26) % 2 == 0 ? &m.offset_corner_latitude_deg[point] : &m.offset_corner_longitude_deg[point];
  }
  if (tag >= 82 && tag <= 89) {  // full corners, same order
    const std::size_t point = (tag - 82) / 2;
    return (tag - 82) % 2 == 0 ? &m.corner_latitude_deg[point] : &m.corner_longitude_deg[point];
  }
  return nullptr;
}

std::optional<LinearMapping> mapping_for(std::uint64_t tag) {
  switch (tag) {
    case 5: return LinearMapping{2, false, 0, 360};
    case 6: return LinearMapping{2, true, -20, 20};
    case 7: return LinearMapping{2, true, -50, 50};
    case 13: case 23: return LinearMapping{4, true, -90, 90};
    case 14: case 24: return LinearMapping{4, true, -180, 180};
    case 15: case 25: return LinearMapping{2, false, -900, 19000};
    case 16: case 17: return LinearMapping{2, false, 0, 180};
    case 18: case 20: return LinearMapping{4, false, 0, 360};
    case 19: return LinearMapping{4, true, -180, 180};
    case 21: return LinearMapping{4, false, 0, 5000000};
    case 22: return LinearMapping{2, false, 0, 10000};
    default: break;
  }
  if (tag >= 26 && tag <= 33) return LinearMapping{2, true, -0.075, 0.075};
  if (tag >= 82 && tag <= 89) return LinearMapping{4, true, (tag % 2 == 0) ? -90.0 : -180.0, (tag % 2 == 0) ? 90.0 : 180.0};
  return std::nullopt;
}

// nullopt for the error indicator.
std::optional<double> apply_mapping(const LinearMapping& map, Bytes value) {
  const std::uint64_t raw = read_be_unsigned(value);
  const int bits = static_cast<int>(8 * map.size);
  const double span = std::ldexp(1.0, bits);  // 2^(8n)
  if (!map.is_signed) return map.min + static_cast<double>(raw) * (map.max - map.min) / (span - 1.0);
  const std::uint64_t sign_bit = std::uint64_t{1} << (bits - 1);
  if (raw == sign_bit) return std::nullopt;
  const double v = (raw & sign_bit) != 0 ? static_cast<double>(raw) - span : static_cast<double>(raw);
  return v * (map.max - map.min) / (span - 2.0);
}

std::string at(std::size_t pos) { return "ST 0601 packet, byte " + std::to_string(pos); }

void decode_item(UasMetadata& m, std::uint64_t tag, Bytes value) {
  if (tag == 2) {
    if (value.size() != 8) return void(++m.malformed_items);
    m.precision_time_us = read_be_unsigned(value);
    return;
  }
  if (tag == 65) {
    if (value.size() != 1) return void(++m.malformed_items);
    m.ls_version = value[0];
    return;
  }
  const auto map = mapping_for(tag);
  if (!map) return void(++m.unknown_items);
  if (value.size() != map->size) return void(++m.malformed_items);
  const auto decoded = apply_mapping(*map, value);
  if (!decoded) ++m.error_values;
  *field_for(m, tag) = decoded;
}

}  // namespace

std::uint16_t st0601_checksum(Bytes bytes) {
  std::uint16_t sum = 0;
  for (std::size_t i = 0; i < bytes.size(); ++i) sum = static_cast<std::uint16_t>(sum + (bytes[i] << (8 * ((i + 1) % 2))));
  return sum;
}

UasMetadata decode_st0601(Bytes packet) {
  if (packet.size() < kSt0601Key.size() || !std::equal(kSt0601Key.begin(), kSt0601Key.end(), packet.begin())) {
    throw InputError("ST 0601 packet: the key is not the UAS Datalink Local Set key 06 0E 2B 34 02 0B 01 01 0E 01 03 01 01 00 00 00");
  }
  const auto length = read_ber_length(packet, kSt0601Key.size());
  if (!length) throw InputError(at(kSt0601Key.size()) + ": BER length cut short or longer than 8 bytes");
  const std::size_t start = kSt0601Key.size() + length->size;
  if (length->value > packet.size() - start) {
    throw InputError("ST 0601 packet: its length " + std::to_string(length->value) + " runs past the " +
                     std::to_string(packet.size() - start) + " bytes after the key");
  }
  const Bytes set = packet.first(start + static_cast<std::size_t>(length->value));

  UasMetadata m;
  m.standard = MetadataStandard::kSt0601;
  std::size_t pos = start;
  while (pos < set.size()) {
    const auto tag = read_ber_oid(set, pos);
    if (!tag) throw InputError(at(pos) + ": item tag cut short");
    const auto item_length = read_ber_length(set, pos + tag->size);
    if (!item_length) throw InputError(at(pos) + ": length of tag " + std::to_string(tag->value) + " cut short");
    const std::size_t value_pos = pos + tag->size + item_length->size;
    if (item_length->value > set.size() - value_pos) {
      throw InputError(at(pos) + ": tag " + std::to_string(tag->value) + " has length " + std::to_string(item_length->value) +
                       ", past the end of the set");
    }
    const Bytes value = set.subspan(value_pos, static_cast<std::size_t>(item_length->value));
    if (tag->value == 1) {
      // The sum covers everything up to and including this item's tag and length bytes.
      m.checksum_computed = st0601_checksum(set.first(value_pos));
      if (value.size() == 2) {
        m.checksum_stored = static_cast<std::uint16_t>(read_be_unsigned(value));
        m.checksum_ok = *m.checksum_stored == m.checksum_computed;
      } else {
        ++m.malformed_items;
        m.checksum_ok = false;
      }
    } else {
      decode_item(m, tag->value, value);
    }
    pos = value_pos + value.size();
  }
  return m;
}

}  // namespace uavmot::geo
