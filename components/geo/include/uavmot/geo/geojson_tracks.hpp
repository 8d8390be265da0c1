#pragma once
// Tracks on the map as GeoJSON (RFC 7946): a FeatureCollection with one Feature per track, a
// LineString of [longitude, latitude] positions (the track's image centres mapped through each
// frame's ground geometry), and properties id, first_time_s, last_time_s, first_frame,
// last_frame, mean_speed_mps (ground length of the line / (last_time_s - first_time_s), 0 for a
// zero duration). Frame k is at time (k - 1) / fps. Deterministic: features by ascending id,
// degrees rounded to 7 decimals (about 1 cm), times to 6, speeds to 3.

#include <cstddef>
#include <filesystem>
#include <optional>
#include <vector>

#include <nlohmann/json.hpp>
#include <opencv2/core/types.hpp>

#include "uavmot/geo/frame_geometry.hpp"

namespace uavmot::geo {

struct TrackPoint {
  int frame = 0;               // 1-based
  cv::Point2d center_px;       // image centre of the object in that frame
};

struct TrackPath {
  int id = 0;
  std::vector<TrackPoint> points;  // any order; sorted by frame on output
};

struct GeoJsonCounts {
  std::size_t features = 0;
  std::size_t skipped_points = 0;  // no ground mapping for their frame
  std::size_t skipped_tracks = 0;  // fewer than two mapped points (a LineString needs two)
};

// frames[k - 1] is frame k's geometry (FlightMetadata::frames). Throws InvalidArgument when fps
// is not positive.
nlohmann::json tracks_to_geojson(const std::vector<TrackPath>& tracks, const std::vector<std::optional<FrameGeometry>>& frames,
                                 double fps, GeoJsonCounts* counts = nullptr);

// Writes tracks_to_geojson() to `path` (2-space indent, trailing newline); InputError when the
// file cannot be written.
GeoJsonCounts write_tracks_geojson(const std::filesystem::path& path, const std::vector<TrackPath>& tracks,
                                   const std::vector<std::optional<FrameGeometry>>& frames, double fps);

}  // namespace uavmot::geo
