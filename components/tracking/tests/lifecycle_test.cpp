// Track lifecycle: confirmation, coasting, dormancy, deletion (deleter.hpp).
#include <gtest/gtest.h>

#include "deleter.hpp"
#include "kalman_model.hpp"

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

TEST(Lifecycle, OneLinkedFeatureConfirmsOnlyOnGroundThatHasJustComeIntoView) {
  TrackerOptions o;
  TrackRecord t = new_track();
  t.features = {FeatureLink{1, {0, 0}, 1}};
  TrackRecord on_new_ground = t;
  record_frame(t, true, false, o, true, 0.0, true, false);
  EXPECT_EQ(t.state, TrackState::Tentative);  // 2 hits, 1 feature: waits for a third hit
  record_frame(on_new_ground, true, false, o, true, 0.0, true, true);
  EXPECT_EQ(on_new_ground.state, TrackState::Confirmed);
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

TEST(Lifecycle, AnEstablishedTrackBridgesShortGapsInsideTheView) {
  TrackerOptions o;
  o.gap_frames = 2;
  o.gap_min_hits = 15;
  TrackRecord t = new_track();
  t.state = TrackState::Confirmed;
  t.hits = 15;
  record_frame(t, false, false, o);
  record_frame(t, false, false, o);
  EXPECT_EQ(t.state, TrackState::Confirmed);  // two frames without a region: still reported
  record_frame(t, false, false, o);
  EXPECT_EQ(t.state, TrackState::Coasting);   // a third: coasting
  // A young track, or one at the image border (leaving), coasts at once.
  TrackRecord young = new_track();
  young.state = TrackState::Confirmed;
  young.hits = 14;
  record_frame(young, false, false, o);
  EXPECT_EQ(young.state, TrackState::Coasting);
  TrackRecord leaving = new_track();
  leaving.state = TrackState::Confirmed;
  leaving.hits = 100;
  record_frame(leaving, false, false, o, /*may_bridge_gap=*/false);
  EXPECT_EQ(leaving.state, TrackState::Coasting);
}

TEST(Lifecycle, WhollyInsideViewNeedsEveryCorner) {
  EXPECT_TRUE(wholly_inside_view(OrientedBox{-100, -100, 5, 15, 0}, cv::Size()));  // image size unknown
  const cv::Size image(200, 100);
  EXPECT_TRUE(wholly_inside_view(OrientedBox{100, 50, 5, 15, 0}, image));
  EXPECT_FALSE(wholly_inside_view(OrientedBox{195, 50, 5, 15, 0}, image));  // centre inside, nose outside
}

TEST(Lifecycle, ATrackTouchingTheBorderWaitsUntilItIsIn) {
  // At the border the camera uncovers a static object bit by bit: its box grows, which looks like
  // motion, and its features at the uncovered edge move too. Nothing confirms it there; once clear
  // of the border the same hits do.
  TrackerOptions o;
  TrackRecord t = new_track();
  record_frame(t, true, false, o, true, 0.0, false);
  record_frame(t, true, false, o, true, 0.0, false);
  EXPECT_EQ(t.state, TrackState::Tentative);  // 3 hits, but at the border
  record_frame(t, true, false, o, true, 0.0, true);
  EXPECT_EQ(t.state, TrackState::Confirmed);
  // Linked moving features do not confirm it at the border either (on the real clips the features
  // of uncovered static objects at the edge were classified moving).
  TrackRecord u = new_track();
  u.features = {FeatureLink{1, {0, 0}, 1}, FeatureLink{2, {0.1, 0}, 1}};
  record_frame(u, true, false, o, true, 0.0, false);
  EXPECT_EQ(u.state, TrackState::Tentative);
  record_frame(u, true, false, o, true, 0.0, true);
  EXPECT_EQ(u.state, TrackState::Confirmed);
}

TEST(Lifecycle, ClearOfBorderKeepsTheMarginOnEverySide) {
  // A box 20 px long along x and 10 px wide; the image covers [-0.5, 99.5) x [-0.5, 79.5).
  const cv::Size image(100, 80);
  EXPECT_TRUE(clear_of_border(OrientedBox{50, 40, 10, 20, 0}, image, 3.0));
  EXPECT_FALSE(clear_of_border(OrientedBox{11, 40, 10, 20, 0}, image, 3.0));   // left end at x = 1
  EXPECT_TRUE(clear_of_border(OrientedBox{11, 40, 10, 20, 0}, image, 0.0));    // no margin: inside is enough
  EXPECT_FALSE(clear_of_border(OrientedBox{88, 40, 10, 20, 0}, image, 3.0));   // right end at x = 98
  EXPECT_FALSE(clear_of_border(OrientedBox{50, 6.5, 10, 20, 0}, image, 3.0));  // top at y = 1.5
  EXPECT_FALSE(clear_of_border(OrientedBox{50, 73.5, 10, 20, 0}, image, 3.0)); // bottom at y = 78.5
  EXPECT_TRUE(clear_of_border(OrientedBox{50, 73.5, 10, 20, 0}, cv::Size(), 3.0));  // image size unknown
}

TEST(Lifecycle, EnteringTheViewMeansMovingInThroughEverySideTheBoxReaches) {
  const cv::Size image(100, 80);
  const OrientedBox at_top{50, 4, 10, 20, 90};  // 20 px long down the image; its top end at y = -6
  EXPECT_TRUE(entering_view(at_top, {0.0, 1.0}, image, 1.0, 60.0));    // straight in
  EXPECT_TRUE(entering_view(at_top, {0.8, 1.0}, image, 1.0, 60.0));    // 39 deg off the inward normal
  EXPECT_FALSE(entering_view(at_top, {2.0, 1.0}, image, 1.0, 60.0));   // 63 deg off: along the border
  EXPECT_FALSE(entering_view(at_top, {0.0, -1.0}, image, 1.0, 60.0));  // going out
  EXPECT_FALSE(entering_view(at_top, {0.0, 0.0}, image, 1.0, 60.0));   // not moving
  EXPECT_FALSE(entering_view(at_top, {0.0, 1.0}, image, 1.0, 0.0));    // the rule off
  EXPECT_FALSE(entering_view(at_top, {0.0, 1.0}, cv::Size(), 1.0, 60.0));  // image size unknown
  // In the top-left corner it must come in through both sides.
  const OrientedBox in_corner{4, 4, 10, 20, 45};
  EXPECT_TRUE(entering_view(in_corner, {1.0, 1.0}, image, 1.0, 60.0));
  EXPECT_FALSE(entering_view(in_corner, {0.0, 1.0}, image, 1.0, 60.0));
  // Each side: the bottom and the right need the opposite sign.
  EXPECT_TRUE(entering_view(OrientedBox{50, 76, 10, 20, 90}, {0.0, -1.0}, image, 1.0, 60.0));
  EXPECT_FALSE(entering_view(OrientedBox{50, 76, 10, 20, 90}, {0.0, 1.0}, image, 1.0, 60.0));
  EXPECT_TRUE(entering_view(OrientedBox{96, 40, 10, 20, 0}, {-1.0, 0.0}, image, 1.0, 60.0));
  EXPECT_FALSE(entering_view(OrientedBox{96, 40, 10, 20, 0}, {1.0, 0.0}, image, 1.0, 60.0));
}

TEST(Lifecycle, AtTheBorderOnlyATrackDrivingInWithAFeatureMayConfirm) {
  // A static object the camera uncovers at the top grows upward over the ground: its box centre moves
  // out. A car driving in moves down, into the image, and carries its features with it.
  TrackerOptions o;
  const cv::Size image(100, 80);
  const OrientedBox at_top{50, 4, 5, 12, 90};  // top end at y = -2
  TrackRecord car = new_track();
  car.mean[kVx] = 0.1;
  car.mean[kVy] = 1.0;
  car.features = {FeatureLink{1, {0, 2}, 1}};
  EXPECT_TRUE(may_confirm_at(car, at_top, image, o));
  TrackRecord uncovered = car;
  uncovered.mean[kVy] = -1.0;
  EXPECT_FALSE(may_confirm_at(uncovered, at_top, image, o));
  TrackRecord featureless = car;
  featureless.features.clear();
  EXPECT_FALSE(may_confirm_at(featureless, at_top, image, o));
  o.confirm_entering_max_angle_deg = 0.0;  // the rule off: every track waits until it is in
  EXPECT_FALSE(may_confirm_at(car, at_top, image, o));
  EXPECT_TRUE(may_confirm_at(car, OrientedBox{50, 40, 5, 12, 90}, image, o));  // inside
  EXPECT_TRUE(may_confirm_at(uncovered, OrientedBox{50, 40, 5, 12, 90}, image, o));
}

TEST(Lifecycle, LeavingTheViewHidesAtOnce) {
  TrackerOptions o;
  const cv::Size image(100, 80);
  EXPECT_TRUE(inside_view(OrientedBox{50, 40, 5, 15, 0}, image));
  EXPECT_FALSE(inside_view(OrientedBox{101, 40, 5, 15, 0}, image));
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
