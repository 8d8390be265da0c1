#include "uavmot/geo/geojson_tracks.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>

#include "uavmot/core/error.hpp"

namespace uavmot::geo {

namespace {

double rounded(double value, int decimals) {
  const double scale = std::pow(10.0, decimals);
  const double r = std::round(value * scale) / scale;
  return r == 0.0 ? 0.0 : r;  // no "-0.0" in the output
}

struct MappedPoint {
  int frame;
  LatLon position;
};

}  // namespace

nlohmann::json tracks_to_geojson(const std::vector<TrackPath>& tracks, const std::vector<std::optional<FrameGeometry>>& frames,
                                 double fps, GeoJsonCounts* counts) {
  if (!(fps > 0.0) || !std::isfinite(fps)) throw InvalidArgument("tracks_to_geojson: fps must be positive");
  GeoJsonCounts local;
  GeoJsonCounts& c = counts ? *counts : local;
  c = {};

  std::vector<const TrackPath*> sorted;
  for (const TrackPath& t : tracks) sorted.push_back(&t);
  std::stable_sort(sorted.begin(), sorted.end(), [](const TrackPath* a, const TrackPath* b) { return a->id < b->id; });

  nlohmann::json features = nlohmann::json::array();
  for (const TrackPath* track : sorted) {
    std::vector<TrackPoint> points = track->points;
    std::stable_sort(points.begin(), points.end(), [](const TrackPoint& a, const TrackPoint& b) { return a.frame < b.frame; });
    std::vector<MappedPoint> mapped;
    for (const TrackPoint& p : points) {
      const bool in_range = p.frame >= 1 && static_cast<std::size_t>(p.frame) <= frames.size();
      const auto& geometry = in_range ? frames[static_cast<std::size_t>(p.frame - 1)] : std::nullopt;
      const auto position = geometry ? geometry->pixel_to_lat_lon(p.center_px) : std::nullopt;
      if (!position) {
        ++c.skipped_points;
        continue;
      }
      mapped.push_back({p.frame, *position});
    }
    if (mapped.size() < 2) {
      ++c.skipped_tracks;
      continue;
    }
    nlohmann::json coordinates = nlohmann::json::array();
    double length_m = 0.0;
    for (std::size_t i = 0; i < mapped.size(); ++i) {
      coordinates.push_back({rounded(mapped[i].position.lon_deg, 7), rounded(mapped[i].position.lat_deg, 7)});
      if (i > 0) length_m += ground_distance_m(mapped[i - 1].position, mapped[i].position);
    }
    const double first_time = (mapped.front().frame - 1) / fps;
    const double last_time = (mapped.back().frame - 1) / fps;
    const double duration = last_time - first_time;
    nlohmann::json feature = {
        {"type", "Feature"},
        {"geometry", {{"type", "LineString"}, {"coordinates", std::move(coordinates)}}},
        {"properties",
         {{"id", track->id},
          {"first_time_s", rounded(first_time, 6)},
          {"last_time_s", rounded(last_time, 6)},
          {"first_frame", mapped.front().frame},
          {"last_frame", mapped.back().frame},
          {"mean_speed_mps", duration > 0.0 ? rounded(length_m / duration, 3) : 0.0}}},
    };
    features.push_back(std::move(feature));
    ++c.features;
  }
  return {{"type", "FeatureCollection"}, {"features", std::move(features)}};
}

GeoJsonCounts write_tracks_geojson(const std::filesystem::path& path, const std::vector<TrackPath>& tracks,
                                   const std::vector<std::optional<FrameGeometry>>& frames, double fps) {
  GeoJsonCounts counts;
  const nlohmann::json doc = tracks_to_geojson(tracks, frames, fps, &counts);
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) throw InputError(path.string() + ": cannot open for writing");
  out << doc.dump(2) << '\n';
  out.flush();
  if (!out) throw InputError(path.string() + ": write failed");
  return counts;
}

}  // namespace uavmot::geo
