// Track initiation: which free regions start tracks (initiator.hpp).
#include <gtest/gtest.h>

#include "initiator.hpp"
#include "kalman_model.hpp"

namespace uavmot::tracking {
namespace {

// At the default scene (0.35 m/px, 25 fps) a car is 12.9 x 5.1 px; 1 px/frame is 8.75 m/s.
const SceneInfo kScene;

// A confirmed track on a 15 px trailer at (100, 100) driving along +x at 1 px/frame.
TrackerState one_trailer(TrackState state = TrackState::Confirmed) {
  TrackerState s;
  TrackRecord t;
  t.id = 1;
  t.state = state;
  t.hits = 20;
  store(initial_state(OrientedBox{100, 100, 7, 15, 0}, cv::Vec2d(1.0, 0.0), 0.1, BoxMeasurementNoise{}), t);
  s.tracks.push_back(t);
  s.next_id = 2;
  return s;
}

size_t started_after(TrackerState state, const OrientedBox& region) {
  const std::vector<OrientedBox> live = {OrientedBox{100, 100, 7, 15, 0}};
  const FrameInput input{identity_homography(), {region}, FeatureIndex({}), cv::Size()};
  initiate_tracks({0}, input, live, TrackerOptions{}, kScene, state);
  return state.tracks.size() - 1;
}

TEST(Initiator, ASmallBlobAtTheNoseOfAMovingVehicleIsPartOfIt) {
  // A windscreen bar 2 x 6 px across the road, 4 px ahead of the trailer's box: the truck's cab.
  const OrientedBox bar{100 + 7.5 + 4 + 1, 100, 2, 6, 90};
  EXPECT_EQ(started_after(one_trailer(), bar), 0u);
}

TEST(Initiator, ACarSizedRegionThereIsANewVehicle) {
  const OrientedBox car{100 + 7.5 + 4 + 6.5, 100, 5, 13, 0};
  EXPECT_EQ(started_after(one_trailer(), car), 1u);
}

TEST(Initiator, ABlobInTheNextLaneOrFarAheadOrBesideATentativeTrackStartsATrack) {
  const OrientedBox next_lane{100 + 7.5 + 4 + 1, 110, 2, 6, 90};
  const OrientedBox far_ahead{100 + 7.5 + 12 + 1, 100, 2, 6, 90};
  const OrientedBox bar{100 + 7.5 + 4 + 1, 100, 2, 6, 90};
  EXPECT_EQ(started_after(one_trailer(), next_lane), 1u);
  EXPECT_EQ(started_after(one_trailer(), far_ahead), 1u);
  EXPECT_EQ(started_after(one_trailer(TrackState::Tentative), bar), 1u);
}

}  // namespace
}  // namespace uavmot::tracking
