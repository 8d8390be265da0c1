// Bad input never crashes the tracker; results are deterministic; saved state resumes exactly.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "synthetic_scene.hpp"
#include "uavmot/core/error.hpp"

namespace uavmot::tracking::testing {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::vector<ObjectPath> two_cars() {
  ObjectPath a;
  a.truth_id = 1;
  a.ground_centre = straight({100, 200}, {1.5, 0.3});
  ObjectPath b;
  b.truth_id = 2;
  b.ground_centre = straight({400, 300}, {-1.2, 0.4});
  return {a, b};
}

bool same_tracks(const TrackList& a, const TrackList& b) {
  if (a.tracks.size() != b.tracks.size()) return false;
  for (size_t i = 0; i < a.tracks.size(); ++i) {
    const Track& x = a.tracks[i];
    const Track& y = b.tracks[i];
    if (x.id != y.id || x.state != y.state || !(x.box == y.box) || x.velocity != y.velocity ||
        x.sigma_x != y.sigma_x || x.age != y.age || x.frames_since_update != y.frames_since_update ||
        x.feature_ids != y.feature_ids) {
      return false;
    }
  }
  return true;
}

TEST(TrackerRobustness, NonFiniteInputIsIgnored) {
  SyntheticScene scene(two_cars(), moving_camera({0.5, -0.3}, 0.1, 1.001));
  Tracker tracker;
  int bad_frames = 0;
  for (int k = 1; k <= 80; ++k) {
    SyntheticFrame f = scene.next();
    if (k % 7 == 0) {  // a NaN region beside the real ones
      Region r;
      r.box = OrientedBox{kNaN, 10, 5, 15, 0};
      f.segmentation.regions.push_back(r);
      Region inf;
      inf.box = OrientedBox{50, 50, std::numeric_limits<double>::infinity(), 15, 0};
      f.segmentation.regions.push_back(inf);
    }
    if (k % 11 == 0) {  // a NaN feature velocity and position
      TrackedFeature bad;
      bad.id = 777;
      bad.moving = true;
      bad.position = {kNaN, 3};
      bad.velocity = {1, kNaN};
      f.motion.features.push_back(bad);
    }
    if (k == 40 || k == 41) {  // broken homographies
      f.motion.homography(0, 2) = kNaN;
      ++bad_frames;
    }
    if (k == 50) f.motion.homography = Homography::zeros();
    const TrackList out = tracker.process(f.motion, f.segmentation);
    for (const auto& t : out.tracks) {
      ASSERT_TRUE(is_finite(t.box)) << "frame " << k;
      ASSERT_TRUE(std::isfinite(t.velocity[0]) && std::isfinite(t.velocity[1]));
    }
    if (k > 20) {
      EXPECT_EQ(out.tracks.size(), 2u) << "frame " << k;  // both cars survive the bad frames
    }
  }
  const TrackerState st = tracker.state();
  EXPECT_EQ(st.rejected_homographies, 3u);
  EXPECT_GT(st.rejected_regions, 0u);
  EXPECT_GT(st.rejected_features, 0u);
  EXPECT_EQ(bad_frames, 2);
}

TEST(TrackerRobustness, EmptyInputGivesNoTracks) {
  Tracker tracker;
  const TrackList out = tracker.process(MotionEstimate{}, SegmentationResult{});
  EXPECT_TRUE(out.tracks.empty());
}

TEST(TrackerRobustness, SameInputSameOutputBitForBit) {
  SceneOptions opts;
  opts.merge_close_objects = true;
  SyntheticScene scene_a(two_cars(), moving_camera({0.5, -0.3}, 0.1, 1.001), opts);
  SyntheticScene scene_b(two_cars(), moving_camera({0.5, -0.3}, 0.1, 1.001), opts);
  Tracker a;
  Tracker b;
  for (int k = 1; k <= 60; ++k) {
    const SyntheticFrame fa = scene_a.next();
    const SyntheticFrame fb = scene_b.next();
    ASSERT_TRUE(same_tracks(a.process(fa.motion, fa.segmentation), b.process(fb.motion, fb.segmentation))) << k;
  }
}

TEST(TrackerRobustness, RestoredStateContinuesIdentically) {
  SyntheticScene scene(two_cars(), moving_camera({0.5, -0.3}, 0.1, 1.001));
  Tracker original;
  std::vector<SyntheticFrame> frames;
  for (int k = 1; k <= 70; ++k) frames.push_back(scene.next());
  for (int k = 0; k < 40; ++k) original.process(frames[static_cast<size_t>(k)].motion, frames[static_cast<size_t>(k)].segmentation);
  Tracker resumed;
  resumed.restore(original.state());
  for (size_t k = 40; k < frames.size(); ++k) {
    const TrackList a = original.process(frames[k].motion, frames[k].segmentation);
    const TrackList b = resumed.process(frames[k].motion, frames[k].segmentation);
    ASSERT_FALSE(a.tracks.empty());
    ASSERT_TRUE(same_tracks(a, b)) << "frame " << k + 1;
  }
}

TEST(TrackerRobustness, RestoreRejectsInconsistentState) {
  TrackerState st;
  TrackRecord r;
  r.id = 5;
  st.next_id = 3;  // id 5 >= next_id
  st.tracks.push_back(r);
  Tracker tracker;
  EXPECT_THROW(tracker.restore(st), InvalidArgument);
  st.next_id = 6;
  st.tracks[0].mean[0] = kNaN;
  EXPECT_THROW(tracker.restore(st), InvalidArgument);
  st.tracks[0].mean[0] = 0.0;
  st.tracks[0].mean[4] = st.tracks[0].mean[5] = 5.0;  // a box, not a point
  ASSERT_NO_THROW(tracker.restore(st));
  st.tracks[0].travel_from.y = kNaN;
  EXPECT_THROW(tracker.restore(st), InvalidArgument);
}

// Counters at their limit would overflow on the next frame (a fuzzed sample had frames_processed
// = INT64_MAX: tests/fuzz/regressions/sample_validators/tracker_frames_at_int64_max).
TEST(TrackerRobustness, RestoreRejectsCountersThatCannotGoOn) {
  Tracker tracker;
  TrackerState st;
  st.frames_processed = std::numeric_limits<int64_t>::max();
  EXPECT_THROW(tracker.restore(st), InvalidArgument);
  st.frames_processed = -1;
  EXPECT_THROW(tracker.restore(st), InvalidArgument);
  st.frames_processed = 7;
  st.next_id = 0;
  EXPECT_THROW(tracker.restore(st), InvalidArgument);
  st.next_id = std::numeric_limits<uint64_t>::max();
  EXPECT_THROW(tracker.restore(st), InvalidArgument);
  st.next_id = 1;
  EXPECT_NO_THROW(tracker.restore(st));
}

TEST(TrackerRobustness, IdsStartAtOneAndIncrease) {
  SyntheticScene scene(two_cars(), static_camera());
  Tracker tracker;
  const SyntheticFrame f = scene.next();
  const TrackList out = tracker.process(f.motion, f.segmentation);
  ASSERT_EQ(out.tracks.size(), 2u);
  EXPECT_EQ(out.tracks[0].id, 1u);
  EXPECT_EQ(out.tracks[1].id, 2u);
  EXPECT_EQ(out.tracks[0].state, TrackState::Tentative);
}

}  // namespace
}  // namespace uavmot::tracking::testing
