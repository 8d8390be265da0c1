#pragma once
// The AFRL POS text record of a CLIF 2007 frame (data/clif2007/pos/*.txt): one line of 14
// comma-separated numbers, or 15 with a leading source name. The field order is the one Kitware's
// kwiver reads and writes (vital/io/metadata_io.cxx, read_pos_file / write_pos_file):
//   yaw, pitch, roll (deg), latitude, longitude (deg), altitude (feet), GPS seconds of week,
//   GPS week, north, east, up velocity, IMU status, local adjustment, DST flags.
// kwiver names the velocities but not their unit; in the CLIF files they match the metres per
// second between consecutive positions (clif_pos_test.cpp checks it).

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "uavmot/geo/local_tangent_plane.hpp"

namespace uavmot::geo {

struct ClifPosRecord {
  std::optional<std::string> source_name;  // only in 15-field lines
  double yaw_deg = 0.0;
  double pitch_deg = 0.0;
  double roll_deg = 0.0;
  double latitude_deg = 0.0;
  double longitude_deg = 0.0;
  double altitude_ft = 0.0;
  double gps_seconds_of_week = 0.0;
  int gps_week = 0;
  double north_velocity_mps = 0.0;
  double east_velocity_mps = 0.0;
  double up_velocity_mps = 0.0;
  int imu_status = 0;
  int local_adjustment = 0;
  int dst_flags = 0;

  double altitude_m() const { return altitude_ft * 0.3048; }
  LatLon position() const { return {latitude_deg, longitude_deg}; }
};

// `where` names the line in error messages. Throws InputError for a wrong field count, a field
// that is not a number (or not an integer where one is due), or a latitude/longitude out of range.
ClifPosRecord parse_clif_pos_line(std::string_view line, const std::string& where);
// The first line of a POS file.
ClifPosRecord read_clif_pos_file(const std::filesystem::path& path);

}  // namespace uavmot::geo
