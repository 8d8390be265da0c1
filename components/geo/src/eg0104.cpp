#include "uavmot/geo/eg0104.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <string>

#include "uavmot/core/error.hpp"

namespace uavmot::geo {

namespace {

using Key = std::array<std::uint8_t, 16>;

// RP 210 element keys EG 0104 uses; the version byte (index 7) is left 0 and ignored when matching.
constexpr Key key(std::uint8_t a, std::uint8_t b, std::uint8_t c, std::uint8_t d, std::uint8_t e, std::uint8_t f,
                  std::uint8_t g, std::uint8_t h) {
  return {0x06, 0x0E, 0x2B, 0x34, 0x01, 0x01, 0x01, 0x00, a, b, c, d, e, f, g, h};
}

constexpr Key kTimeStamp = key(0x07, 0x02, 0x01, 0x01, 0x01, 0x05, 0x00, 0x00);  // user defined time stamp, µs since 1970
constexpr Key kDeviceLatitude = key(0x07, 0x01, 0x02, 0x01, 0x02, 0x04, 0x02, 0x00);
constexpr Key kDeviceLongitude = key(0x07, 0x01, 0x02, 0x01, 0x02, 0x06, 0x02, 0x00);
constexpr Key kDeviceAltitude = key(0x07, 0x01, 0x02, 0x01, 0x02, 0x02, 0x00, 0x00);
constexpr Key kPlatformRoll = key(0x07, 0x01, 0x10, 0x01, 0x04, 0x00, 0x00, 0x00);
constexpr Key kPlatformPitch = key(0x07, 0x01, 0x10, 0x01, 0x05, 0x00, 0x00, 0x00);
constexpr Key kPlatformHeading = key(0x07, 0x01, 0x10, 0x01, 0x06, 0x00, 0x00, 0x00);
constexpr Key kHorizontalFov = key(0x04, 0x20, 0x02, 0x01, 0x01, 0x08, 0x00, 0x00);
constexpr Key kVerticalFov = key(0x04, 0x20, 0x02, 0x01, 0x01, 0x0A, 0x01, 0x00);
constexpr Key kSlantRange = key(0x07, 0x01, 0x08, 0x01, 0x01, 0x00, 0x00, 0x00);
constexpr Key kTargetWidth = key(0x07, 0x01, 0x09, 0x02, 0x01, 0x00, 0x00, 0x00);
constexpr Key kAngleToNorth = key(0x07, 0x01, 0x10, 0x01, 0x02, 0x00, 0x00, 0x00);
constexpr Key kObliquityAngle = key(0x07, 0x01, 0x10, 0x01, 0x03, 0x00, 0x00, 0x00);
constexpr Key kFrameCenterLatitude = key(0x07, 0x01, 0x02, 0x01, 0x03, 0x02, 0x00, 0x00);
constexpr Key kFrameCenterLongitude = key(0x07, 0x01, 0x02, 0x01, 0x03, 0x04, 0x00, 0x00);
// Corner latitudes 1-4 are ...03 07..0A, longitudes ...03 0B..0E (the caller adds the point).
constexpr Key kCornerLatitude1 = key(0x07, 0x01, 0x02, 0x01, 0x03, 0x07, 0x01, 0x00);
constexpr Key kCornerLongitude1 = key(0x07, 0x01, 0x02, 0x01, 0x03, 0x0B, 0x01, 0x00);

bool same_key(Bytes element_key, const Key& expected) {
  for (std::size_t i = 0; i < expected.size(); ++i) {
    if (i != 7 && element_key[i] != expected[i]) return false;
  }
  return true;
}

// Corner point (0-3) when `element_key` is the corner key `first` with its byte 13 advanced.
std::optional<std::size_t> corner_point(Bytes element_key, const Key& first) {
  Key k = first;
  for (std::uint8_t point = 0; point < 4; ++point) {
    k[13] = static_cast<std::uint8_t>(first[13] + point);
    if (same_key(element_key, k)) return point;
  }
  return std::nullopt;
}

// IEEE-754 big-endian float (4 bytes) or double (8); nullopt for other sizes.
std::optional<double> read_real(Bytes value) {
  if (value.size() == 4) return static_cast<double>(std::bit_cast<float>(static_cast<std::uint32_t>(read_be_unsigned(value))));
  if (value.size() == 8) return std::bit_cast<double>(read_be_unsigned(value));
  return std::nullopt;
}

std::optional<double>* real_field(UasMetadata& m, Bytes k) {
  if (same_key(k, kDeviceLatitude)) return &m.sensor_latitude_deg;
  if (same_key(k, kDeviceLongitude)) return &m.sensor_longitude_deg;
  if (same_key(k, kDeviceAltitude)) return &m.sensor_true_altitude_m;
  if (same_key(k, kPlatformRoll)) return &m.platform_roll_deg;
  if (same_key(k, kPlatformPitch)) return &m.platform_pitch_deg;
  if (same_key(k, kPlatformHeading)) return &m.platform_heading_deg;
  if (same_key(k, kHorizontalFov)) return &m.sensor_hfov_deg;
  if (same_key(k, kVerticalFov)) return &m.sensor_vfov_deg;
  if (same_key(k, kSlantRange)) return &m.slant_range_m;
  if (same_key(k, kTargetWidth)) return &m.target_width_m;
  if (same_key(k, kAngleToNorth)) return &m.sensor_angle_to_north_deg;
  if (same_key(k, kObliquityAngle)) return &m.sensor_obliquity_deg;
  if (same_key(k, kFrameCenterLatitude)) return &m.frame_center_latitude_deg;
  if (same_key(k, kFrameCenterLongitude)) return &m.frame_center_longitude_deg;
  if (const auto p = corner_point(k, kCornerLatitude1)) return &m.corner_latitude_deg[*p];
  if (const auto p = corner_point(k, kCornerLongitude1)) return &m.corner_longitude_deg[*p];
  return nullptr;
}

std::string at(std::size_t pos) { return "EG 0104 packet, byte " + std::to_string(pos); }

}  // namespace

UasMetadata decode_eg0104(Bytes packet) {
  if (packet.size() < kEg0104Key.size() || !std::equal(kEg0104Key.begin(), kEg0104Key.end(), packet.begin())) {
    throw InputError("EG 0104 packet: the key is not the Predator UAV Basic Universal Metadata Set key");
  }
  const auto length = read_ber_length(packet, kEg0104Key.size());
  if (!length) throw InputError(at(kEg0104Key.size()) + ": BER length cut short or longer than 8 bytes");
  const std::size_t start = kEg0104Key.size() + length->size;
  if (length->value > packet.size() - start) {
    throw InputError("EG 0104 packet: its length " + std::to_string(length->value) + " runs past the " +
                     std::to_string(packet.size() - start) + " bytes after the key");
  }
  const Bytes set = packet.first(start + static_cast<std::size_t>(length->value));

  UasMetadata m;
  m.standard = MetadataStandard::kEg0104;
  std::size_t pos = start;
  while (pos < set.size()) {
    if (set.size() - pos < kUniversalKeySize + 1) throw InputError(at(pos) + ": element key cut short");
    const Bytes element_key = set.subspan(pos, kUniversalKeySize);
    const auto element_length = read_ber_length(set, pos + kUniversalKeySize);
    if (!element_length) throw InputError(at(pos) + ": element length cut short");
    const std::size_t value_pos = pos + kUniversalKeySize + element_length->size;
    if (element_length->value > set.size() - value_pos) {
      throw InputError(at(pos) + ": element length " + std::to_string(element_length->value) + " runs past the end of the set");
    }
    const Bytes value = set.subspan(value_pos, static_cast<std::size_t>(element_length->value));
    pos = value_pos + value.size();

    if (same_key(element_key, kTimeStamp)) {
      if (value.size() == 8) {
        m.precision_time_us = read_be_unsigned(value);
      } else {
        ++m.malformed_items;
      }
      continue;
    }
    std::optional<double>* field = real_field(m, element_key);
    if (!field) {
      ++m.unknown_items;
      continue;
    }
    const auto real = read_real(value);
    if (!real) {
      ++m.malformed_items;
    } else if (!std::isfinite(*real)) {
      ++m.error_values;  // NaN or infinity: treat as missing
    } else {
      *field = *real;
    }
  }
  return m;
}

}  // namespace uavmot::geo
