#include "uavmot/geo/track_map.hpp"

#include <limits>

#include "uavmot/core/error.hpp"

namespace uavmot::geo {

void TrackMapRecorder::add(const TrackList& tracks) {
  if (tracks.frame_index < 1 || tracks.frame_index > std::numeric_limits<int>::max()) return;
  for (const Track& t : tracks.tracks) {
    if (t.state != TrackState::Confirmed) continue;
    // GeoJSON ids are plain numbers; ids past int range cannot come from a tracker counting from 1.
    if (t.id > static_cast<std::uint64_t>(std::numeric_limits<int>::max())) continue;
    TrackPath& path = paths_[t.id];
    path.id = static_cast<int>(t.id);
    path.points.push_back({static_cast<int>(tracks.frame_index), {t.box.cx, t.box.cy}});
  }
}

std::vector<TrackPath> TrackMapRecorder::paths() const {
  std::vector<TrackPath> out;
  out.reserve(paths_.size());
  for (const auto& [id, path] : paths_) out.push_back(path);
  return out;
}

GeoJsonCounts TrackMapRecorder::write(const std::filesystem::path& path, const std::vector<std::optional<FrameGeometry>>& frames,
                                      double fps) const {
  return write_tracks_geojson(path, paths(), frames, fps);
}

}  // namespace uavmot::geo
