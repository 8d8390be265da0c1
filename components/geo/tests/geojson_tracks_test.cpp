#include "uavmot/geo/geojson_tracks.hpp"

#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "test_data.hpp"
#include "uavmot/build_paths/build_paths.hpp"
#include "uavmot/core/error.hpp"
#include "uavmot/geo/flight_metadata.hpp"

namespace uavmot::geo {
namespace {

constexpr double kFps = 30000.0 / 1001.0;

const FlightMetadata& aphill() {
  static const FlightMetadata f = read_flight_metadata(test::aphill_ts_path(), {720, 480}, kFps);
  return f;
}

TEST(GeoJsonTracks, FeatureCollectionOfLineStrings) {
  const auto& f = aphill();
  // Track 7 moves 4 px right a frame across the middle row; track 3 is listed second but comes first.
  TrackPath moving{7, {}};
  for (int k = 1; k <= 30; ++k) moving.points.push_back({k, {200.0 + 4.0 * (k - 1), 240.0}});
  TrackPath still{3, {{5, {100, 100}}, {6, {100, 100}}}};
  TrackPath lonely{9, {{2, {10, 10}}}};                    // one point: no LineString
  TrackPath outside{11, {{60, {10, 10}}, {61, {20, 20}}}};  // frames without geometry
  GeoJsonCounts counts;
  const nlohmann::json doc = tracks_to_geojson({moving, still, lonely, outside}, f.frames, kFps, &counts);

  EXPECT_EQ(doc["type"], "FeatureCollection");
  ASSERT_EQ(doc["features"].size(), 2u);
  EXPECT_EQ(counts.features, 2u);
  EXPECT_EQ(counts.skipped_tracks, 2u);
  EXPECT_EQ(counts.skipped_points, 2u);

  // A pixel that stays put still moves on the ground when the footprint does: the clip's frame
  // centre moves 0.3-2 m from one packet to the next (camera motion and metadata noise).
  const auto& first = doc["features"][0];
  EXPECT_EQ(first["properties"]["id"], 3);
  const double still_m = ground_distance_m(*f.frame(5)->pixel_to_lat_lon({100, 100}), *f.frame(6)->pixel_to_lat_lon({100, 100}));
  EXPECT_NEAR(first["properties"]["mean_speed_mps"].get<double>(), still_m * kFps, 1e-3);

  const auto& track = doc["features"][1];
  EXPECT_EQ(track["type"], "Feature");
  EXPECT_EQ(track["geometry"]["type"], "LineString");
  const auto& coordinates = track["geometry"]["coordinates"];
  ASSERT_EQ(coordinates.size(), 30u);
  // [longitude, latitude], RFC 7946 order: longitude near -77.35, latitude near 38.25.
  EXPECT_NEAR(coordinates[0][0].get<double>(), -77.354, 0.01);
  EXPECT_NEAR(coordinates[0][1].get<double>(), 38.2456, 0.01);
  const auto& p = track["properties"];
  EXPECT_EQ(p["id"], 7);
  EXPECT_EQ(p["first_frame"], 1);
  EXPECT_EQ(p["last_frame"], 30);
  EXPECT_DOUBLE_EQ(p["first_time_s"].get<double>(), 0.0);
  EXPECT_DOUBLE_EQ(p["last_time_s"].get<double>(), 0.967633);  // 29 / 29.97 s, 6 decimals
  // Mean speed = the line's ground length / its duration.
  double length_m = 0.0;
  for (std::size_t i = 1; i < moving.points.size(); ++i) {
    const TrackPoint& a = moving.points[i - 1];
    const TrackPoint& b = moving.points[i];
    length_m += ground_distance_m(*f.frame(a.frame)->pixel_to_lat_lon(a.center_px), *f.frame(b.frame)->pixel_to_lat_lon(b.center_px));
  }
  EXPECT_NEAR(p["mean_speed_mps"].get<double>(), length_m / (29.0 / kFps), 1e-3);
}

TEST(GeoJsonTracks, DeterministicAndRounded) {
  const auto& f = aphill();
  TrackPath t{1, {{1, {10.123456, 20.5}}, {2, {11.0, 21.0}}}};
  const std::string a = tracks_to_geojson({t}, f.frames, kFps).dump();
  const std::string b = tracks_to_geojson({t}, f.frames, kFps).dump();
  EXPECT_EQ(a, b);
  const nlohmann::json doc = nlohmann::json::parse(a);
  for (const auto& position : doc["features"][0]["geometry"]["coordinates"]) {
    for (const auto& v : position) {
      const double d = v.get<double>();
      EXPECT_NEAR(d * 1e7, std::round(d * 1e7), 1e-3) << d;
    }
  }
}

TEST(GeoJsonTracks, WritesAFile) {
  const std::string path = build_paths::binary_dir() + "/geo_test_tracks.geojson";
  TrackPath t{1, {{1, {10, 20}}, {40, {300, 200}}}};
  const GeoJsonCounts counts = write_tracks_geojson(path, {t}, aphill().frames, kFps);
  EXPECT_EQ(counts.features, 1u);
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_EQ(nlohmann::json::parse(text.str())["features"].size(), 1u);
  EXPECT_THROW(write_tracks_geojson("/nonexistent/dir/t.geojson", {t}, aphill().frames, kFps), InputError);
  EXPECT_THROW(tracks_to_geojson({t}, aphill().frames, 0.0), InvalidArgument);
}

}  // namespace
}  // namespace uavmot::geo
