// geo_footprints TS WIDTH HEIGHT FPS OUT.json: each frame's ground footprint (its four corners as
// [lon, lat], MISB order) for a video of that size and decoded frame rate, as tests/geo_js's
// validate.mjs reads it: {"frames": {"1": [[lon, lat] x 4], ...}}.
#include <cstdio>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "uavmot/geo/flight_metadata.hpp"

int main(int argc, char** argv) {
  using namespace uavmot::geo;
  if (argc != 6) {
    std::fprintf(stderr, "usage: geo_footprints TS WIDTH HEIGHT FPS OUT.json\n");
    return 2;
  }
  try {
    const cv::Size size(std::stoi(argv[2]), std::stoi(argv[3]));
    const FlightMetadata flight = read_flight_metadata(argv[1], size, std::stod(argv[4]));
    nlohmann::json frames = nlohmann::json::object();
    for (int k = 1; k <= static_cast<int>(flight.frames.size()); ++k) {
      const FrameGeometry* g = flight.frame(k);
      if (!g || !g->corners()) continue;
      nlohmann::json ring = nlohmann::json::array();
      for (const LatLon& c : *g->corners()) ring.push_back({c.lon_deg, c.lat_deg});
      frames[std::to_string(k)] = ring;
    }
    std::ofstream(argv[5]) << nlohmann::json{{"frames", frames}}.dump(2) << '\n';
    std::printf("geo_footprints: %zu frames with a footprint\n", frames.size());
    return frames.empty() ? 1 : 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "geo_footprints: %s\n", e.what());
    return 1;
  }
}
