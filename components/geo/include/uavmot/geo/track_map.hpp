#pragma once
// Puts the chain's tracks on the map at the end of a run. TrackMapRecorder keeps, frame by frame,
// the image centre of every confirmed track (the boxes tracks.txt holds); write() maps them
// through each frame's ground geometry into tracks.geojson (geojson_tracks.hpp). `uavmot process`
// and the sink both use it, so given the same tracks and metadata they write the same bytes.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <vector>

#include "uavmot/core/chain_types.hpp"
#include "uavmot/geo/frame_geometry.hpp"
#include "uavmot/geo/geojson_tracks.hpp"

namespace uavmot::geo {

class TrackMapRecorder {
 public:
  // Confirmed tracks only (tentative and coasting ones are not on the map, as in tracks.txt).
  void add(const TrackList& tracks);
  // Ordered by id, points by frame.
  std::vector<TrackPath> paths() const;
  std::size_t tracks() const { return paths_.size(); }
  // Writes `path` (tracks_to_geojson); InputError when it cannot be written.
  GeoJsonCounts write(const std::filesystem::path& path, const std::vector<std::optional<FrameGeometry>>& frames, double fps) const;

 private:
  std::map<std::uint64_t, TrackPath> paths_;
};

}  // namespace uavmot::geo
