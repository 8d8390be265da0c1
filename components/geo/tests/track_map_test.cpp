#include "uavmot/geo/track_map.hpp"

#include <gtest/gtest.h>

#include "scratch_dir.hpp"

namespace uavmot::geo {
namespace {

Track track(uint64_t id, TrackState state, double cx, double cy) {
  Track t;
  t.id = id;
  t.state = state;
  t.box.cx = cx;
  t.box.cy = cy;
  return t;
}

TEST(TrackMapRecorder, KeepsConfirmedCentresByIdAndFrame) {
  TrackMapRecorder recorder;
  recorder.add({"uav1", 1, 0, {track(2, TrackState::Confirmed, 10, 20), track(1, TrackState::Tentative, 5, 5)}});
  recorder.add({"uav1", 2, 0, {track(2, TrackState::Confirmed, 11, 21), track(1, TrackState::Confirmed, 6, 6)}});
  recorder.add({"uav1", 3, 0, {track(2, TrackState::Coasting, 12, 22)}});
  const auto paths = recorder.paths();
  ASSERT_EQ(paths.size(), 2u);
  EXPECT_EQ(paths[0].id, 1);
  ASSERT_EQ(paths[0].points.size(), 1u);  // frame 1 was tentative
  EXPECT_EQ(paths[0].points[0].frame, 2);
  EXPECT_EQ(paths[1].id, 2);
  ASSERT_EQ(paths[1].points.size(), 2u);  // frame 3 was coasting
  EXPECT_EQ(paths[1].points[1].frame, 2);
  EXPECT_DOUBLE_EQ(paths[1].points[1].center_px.x, 11.0);
  EXPECT_DOUBLE_EQ(paths[1].points[1].center_px.y, 21.0);
}

TEST(TrackMapRecorder, WritesAnEmptyCollectionWithoutTracks) {
  TrackMapRecorder recorder;
  const auto path = test_support::scratch_path("track_map_empty.geojson");
  const GeoJsonCounts counts = recorder.write(path, {}, 25.0);
  EXPECT_EQ(counts.features, 0u);
  EXPECT_TRUE(std::filesystem::exists(path));
}

}  // namespace
}  // namespace uavmot::geo
