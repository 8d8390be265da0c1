// geo_make_geojson TS OUT_DIR: writes OUT_DIR/tracks.geojson (synthetic tracks crossing the
// clip's frames) and OUT_DIR/footprints.json (each frame's corner polygon, and for each track the
// frame of each of its LineString positions), for tests/geo_js/validate.mjs.
#include <cstdio>
#include <fstream>

#include <nlohmann/json.hpp>

#include "uavmot/core/error.hpp"
#include "uavmot/geo/flight_metadata.hpp"
#include "uavmot/geo/geojson_tracks.hpp"

int main(int argc, char** argv) {
  using namespace uavmot::geo;
  if (argc != 3) {
    std::fprintf(stderr, "usage: geo_make_geojson TS OUT_DIR\n");
    return 2;
  }
  try {
    constexpr double kFps = 30000.0 / 1001.0;
    const cv::Size size(720, 480);
    const FlightMetadata flight = read_flight_metadata(argv[1], size, kFps);
    const int frames = static_cast<int>(flight.frames.size());
    // Three tracks: left to right, top to bottom, and a diagonal that starts late; all inside the image.
    std::vector<TrackPath> tracks = {{1, {}}, {2, {}}, {3, {}}};
    for (int k = 1; k <= frames; ++k) {
      tracks[0].points.push_back({k, {20.0 + 14.0 * (k - 1), 240.0}});
      tracks[1].points.push_back({k, {360.0, 10.0 + 9.5 * (k - 1)}});
      if (k >= 10) tracks[2].points.push_back({k, {700.0 - 15.0 * (k - 10), 470.0 - 10.0 * (k - 10)}});
    }
    std::filesystem::create_directories(argv[2]);
    const std::filesystem::path out(argv[2]);
    const GeoJsonCounts counts = write_tracks_geojson(out / "tracks.geojson", tracks, flight.frames, kFps);

    nlohmann::json footprints = {{"frames", nlohmann::json::object()}, {"tracks", nlohmann::json::object()}};
    for (int k = 1; k <= frames; ++k) {
      const FrameGeometry* g = flight.frame(k);
      if (!g || !g->corners()) continue;
      nlohmann::json ring = nlohmann::json::array();
      for (const LatLon& c : *g->corners()) ring.push_back({c.lon_deg, c.lat_deg});
      footprints["frames"][std::to_string(k)] = ring;
    }
    for (const TrackPath& t : tracks) {
      nlohmann::json frame_list = nlohmann::json::array();
      for (const TrackPoint& p : t.points) {
        if (flight.frame(p.frame) && flight.frame(p.frame)->has_ground_mapping()) frame_list.push_back(p.frame);
      }
      footprints["tracks"][std::to_string(t.id)] = frame_list;
    }
    std::ofstream(out / "footprints.json") << footprints.dump(2) << '\n';
    std::printf("geo_make_geojson: %zu features, %d frames, median GSD %.4f m/px\n", counts.features, frames,
                flight.summary.median_gsd_m_per_px.value_or(0.0));
    return counts.features == tracks.size() ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "geo_make_geojson: %s\n", e.what());
    return 1;
  }
}
