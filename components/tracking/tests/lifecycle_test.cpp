// Track lifecycle: confirmation, coasting, dormancy, deletion (deleter.hpp).
#include <gtest/gtest.h>

#include "uavmot/tracking/deleter.hpp"

namespace uavmot::tracking {
namespace {

TrackRecord new_track() {
  TrackRecord t;
  t.id = 1;
  t.age = 1;
  t.hits = 1;
  t.hit_history = 1;
  return t;
}

TEST(Lifecycle, ThreeHitsInFiveConfirm) {
  TrackerOptions o;
  TrackRecord t = new_track();
  record_frame(t, true, false, o);
  EXPECT_EQ(t.state, TrackState::Tentative);  // 2 hits, no features
  record_frame(t, false, false, o);
  EXPECT_EQ(decide_fate(t, true, o), Fate::Keep);  // one miss is allowed
  record_frame(t, true, false, o);
  EXPECT_EQ(t.state, TrackState::Confirmed);  // 3 of 4
}

TEST(Lifecycle, LinkedFeaturesConfirmAfterTwoHits) {
  TrackerOptions o;
  TrackRecord t = new_track();
  t.features = {FeatureLink{1, {0, 0}, 1}, FeatureLink{2, {0.1, 0}, 1}};
  record_frame(t, true, false, o);
  EXPECT_EQ(t.state, TrackState::Confirmed);
  o.confirm_hits_with_features = 0;  // disabled: back to 3 of 5
  TrackRecord u = new_track();
  u.features = t.features;
  record_frame(u, true, false, o);
  EXPECT_EQ(u.state, TrackState::Tentative);
}

TEST(Lifecycle, TentativeMissingTwiceIsDeleted) {
  TrackerOptions o;
  TrackRecord t = new_track();
  record_frame(t, false, false, o);
  record_frame(t, false, false, o);
  EXPECT_EQ(decide_fate(t, true, o), Fate::Delete);
}

TEST(Lifecycle, ConfirmedCoastsThenGoesDormant) {
  TrackerOptions o;
  TrackRecord t = new_track();
  t.state = TrackState::Confirmed;
  for (int i = 0; i < o.max_coast_frames; ++i) {
    record_frame(t, false, false, o);
    EXPECT_EQ(t.state, TrackState::Coasting);
    EXPECT_EQ(decide_fate(t, true, o), Fate::Keep);
  }
  record_frame(t, false, false, o);
  EXPECT_EQ(decide_fate(t, true, o), Fate::Dormant);
  // Feature support alone keeps it confirmed.
  TrackRecord s = new_track();
  s.state = TrackState::Confirmed;
  for (int i = 0; i < 20; ++i) record_frame(s, false, true, o);
  EXPECT_EQ(s.state, TrackState::Confirmed);
  EXPECT_EQ(decide_fate(s, true, o), Fate::Keep);
}

TEST(Lifecycle, LeavingTheViewHidesAtOnce) {
  TrackerOptions o;
  o.image_width = 100;
  o.image_height = 80;
  EXPECT_TRUE(inside_view(OrientedBox{50, 40, 5, 15, 0}, o));
  EXPECT_FALSE(inside_view(OrientedBox{101, 40, 5, 15, 0}, o));
  TrackRecord t = new_track();
  t.state = TrackState::Confirmed;
  EXPECT_EQ(decide_fate(t, false, o), Fate::Dormant);
  t.state = TrackState::Tentative;
  EXPECT_EQ(decide_fate(t, false, o), Fate::Delete);
}

TEST(Lifecycle, DormantTracksExpire) {
  TrackerOptions o;
  o.reacquire_max_frames = 3;
  TrackerState st;
  TrackRecord t = new_track();
  t.anchor_box = OrientedBox{10, 10, 5, 15, 0};
  st.dormant.push_back(t);
  const Homography shift(1, 0, 2, 0, 1, 0, 0, 0, 1);
  for (int i = 0; i < 3; ++i) age_dormant(st, shift, o);
  ASSERT_EQ(st.dormant.size(), 1u);
  EXPECT_DOUBLE_EQ(st.dormant[0].anchor_box.cx, 16.0);  // carried by the camera motion
  age_dormant(st, shift, o);
  EXPECT_TRUE(st.dormant.empty());
}

}  // namespace
}  // namespace uavmot::tracking
