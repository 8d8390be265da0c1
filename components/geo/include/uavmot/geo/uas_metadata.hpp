#pragma once
// One decoded UAS metadata packet, whichever MISB set carried it: ST 0601 (UAS Datalink Local Set,
// misb0601.hpp) or its predecessor EG 0104 (Predator UAV Basic Universal Metadata Set, eg0104.hpp,
// which aphill_short.ts carries). Fields a packet does not hold, or holds as the standard's
// "error" value, are nullopt. Angles in degrees, lengths in metres, latitudes/longitudes WGS84.

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>

#include "uavmot/geo/klv.hpp"

namespace uavmot::geo {

enum class MetadataStandard { kSt0601, kEg0104 };

struct UasMetadata {
  MetadataStandard standard = MetadataStandard::kSt0601;

  std::optional<std::uint64_t> precision_time_us;  // 0601 tag 2 / 0104 user defined time stamp, µs since 1970 (UTC)
  std::optional<double> platform_heading_deg;      // tags 5, 6, 7
  std::optional<double> platform_pitch_deg;
  std::optional<double> platform_roll_deg;
  std::optional<double> sensor_latitude_deg;       // tags 13, 14, 15
  std::optional<double> sensor_longitude_deg;
  std::optional<double> sensor_true_altitude_m;
  std::optional<double> sensor_hfov_deg;           // tags 16, 17
  std::optional<double> sensor_vfov_deg;
  std::optional<double> sensor_relative_azimuth_deg;    // tags 18, 19, 20 (ST 0601 only)
  std::optional<double> sensor_relative_elevation_deg;
  std::optional<double> sensor_relative_roll_deg;
  std::optional<double> slant_range_m;             // tag 21
  std::optional<double> target_width_m;            // tag 22
  std::optional<double> frame_center_latitude_deg;   // tags 23, 24, 25
  std::optional<double> frame_center_longitude_deg;
  std::optional<double> frame_center_elevation_m;
  // Corner points 1-4: 1 upper left of the image, then clockwise (2 upper right, 3 lower right,
  // 4 lower left). Offsets (tags 26-33) are degrees added to the frame centre; full corners are
  // tags 82-89 in ST 0601 and the corner elements of EG 0104.
  std::array<std::optional<double>, 4> offset_corner_latitude_deg;
  std::array<std::optional<double>, 4> offset_corner_longitude_deg;
  std::array<std::optional<double>, 4> corner_latitude_deg;
  std::array<std::optional<double>, 4> corner_longitude_deg;
  std::optional<int> ls_version;                   // tag 65
  // EG 0104 only: line-of-sight azimuth from true north, and the obliquity angle.
  std::optional<double> sensor_angle_to_north_deg;
  std::optional<double> sensor_obliquity_deg;

  // Checksum (ST 0601 tag 1): nullopt when the packet has none (EG 0104 never has one).
  std::optional<bool> checksum_ok;
  std::optional<std::uint16_t> checksum_stored;
  std::uint16_t checksum_computed = 0;

  std::size_t unknown_items = 0;    // tags or keys this decoder does not read
  std::size_t malformed_items = 0;  // known tags with a length the standard does not allow (skipped)
  std::size_t error_values = 0;     // values equal to the standard's "error indicator" (left nullopt)
};

// Decodes one KLV unit (key, BER length, value) as ST 0601 or EG 0104, by its key. nullopt for
// other keys (e.g. an ST 0102 security set sent on its own). Throws InputError when the unit has
// a known key but its structure is broken (length past the end, an item cut short).
std::optional<UasMetadata> decode_uas_metadata(Bytes klv_unit);

}  // namespace uavmot::geo
