// Tracker accuracy and identity on synthetic sequences with known truth (synthetic_scene.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <set>

#include "synthetic_scene.hpp"

namespace uavmot::tracking::testing {
namespace {

ObjectPath car(uint64_t id, cv::Point2d start, cv::Vec2d velocity) {
  ObjectPath o;
  o.truth_id = id;
  o.ground_centre = straight(start, velocity);
  return o;
}

// A hovering UAV: the camera shakes (up to ~3 px/frame), sways in rotation and zoom and drifts slowly,
// so every frame-to-frame homography is far from the identity and far from constant.
CameraPath drifting_camera() {
  return [](int frame) {
    const double k = frame - 1;
    const double tx = -0.3 * k + 12.0 * std::sin(2.0 * M_PI * k / 40.0);
    const double ty = 0.2 * k + 9.0 * std::cos(2.0 * M_PI * k / 33.0);
    const double a = (0.03 * k + 1.5 * std::sin(2.0 * M_PI * k / 50.0)) * M_PI / 180.0;
    const double s = 1.0 + 0.0005 * k + 0.02 * std::sin(2.0 * M_PI * k / 60.0);
    const cv::Matx33d to_origin(1, 0, -320, 0, 1, -240, 0, 0, 1);
    const cv::Matx33d rotate_scale(s * std::cos(a), -s * std::sin(a), 0, s * std::sin(a), s * std::cos(a), 0, 0, 0, 1);
    const cv::Matx33d back(1, 0, 320 + tx, 0, 1, 240 + ty, 0, 0, 1);
    return Homography(back * rotate_scale * to_origin);
  };
}

TEST(TrackerScenario, SingleCarSubPixelWithStaticCamera) {
  SyntheticScene scene({car(1, {100, 200}, {1.5, 0.3})}, static_camera());
  Tracker tracker;
  const Score s = run_and_score(scene, tracker, run_for(150));
  EXPECT_EQ(s.matched, s.truth_instances);
  EXPECT_LT(s.mean_position_error, 0.4);
  EXPECT_EQ(s.track_ids_of_truth.at(1).size(), 1u);
  EXPECT_EQ(s.unmatched_confirmed_tracks, 0);
}

TEST(TrackerScenario, SingleCarUnderCameraMotionAsGoodAsStatic) {
  SyntheticScene still({car(1, {100, 200}, {1.5, 0.3})}, static_camera());
  SyntheticScene moving({car(1, {100, 200}, {1.5, 0.3})}, drifting_camera());
  Tracker a;
  Tracker b;
  const Score s_still = run_and_score(still, a, run_for(150));
  const Score s_moving = run_and_score(moving, b, run_for(150));
  EXPECT_EQ(s_moving.matched, s_moving.truth_instances);
  EXPECT_LT(s_moving.mean_position_error, 0.4);
  EXPECT_LT(s_moving.mean_position_error, s_still.mean_position_error + 0.1);
  EXPECT_EQ(s_moving.track_ids_of_truth.at(1).size(), 1u);
}

TEST(TrackerScenario, HomographyControlInputMatters) {
  // Same moving-camera sequence, but the tracker is told the camera stood still: it must do clearly worse.
  SyntheticScene with_control({car(1, {100, 200}, {1.5, 0.3})}, drifting_camera());
  SyntheticScene without_control({car(1, {100, 200}, {1.5, 0.3})}, drifting_camera());
  Tracker a;
  Tracker b;
  RunOptions blind = run_for(150);
  blind.edit_motion = [](MotionEstimate& m) { m.homography = identity_homography(); };
  const Score good = run_and_score(with_control, a, run_for(150));
  const Score bad = run_and_score(without_control, b,
                                  blind);
  EXPECT_LT(good.mean_position_error, 0.4);
  EXPECT_GT(bad.mean_position_error, 2.0 * good.mean_position_error + 0.3);
}

TEST(TrackerScenario, VelocityIsRelativeToTheGround) {
  SyntheticScene scene({car(1, {100, 200}, {1.5, 0.3})}, drifting_camera());
  Tracker tracker;
  double worst = 0.0;
  for (int k = 1; k <= 120; ++k) {
    const SyntheticFrame f = scene.next();
    const TrackList out = tracker.process(f.motion, f.segmentation);
    if (k < 30) continue;
    ASSERT_EQ(out.tracks.size(), 1u);
    worst = std::max(worst, cv::norm(out.tracks[0].velocity - f.truth[0].velocity));
  }
  EXPECT_LT(worst, 0.15);  // px/frame; the camera moves ~1.3 px/frame
}

// Published boxes and velocities are float32 values, so the compact downlink carries them exactly
// (the ground's files equal `uavmot process`'s byte for byte).
TEST(TrackerScenario, PublishedBoxesAndVelocitiesAreFloat32Values) {
  SyntheticScene scene({car(1, {100, 200}, {1.5, 0.3}), car(2, {300, 120}, {-0.7, 1.1})}, drifting_camera());
  Tracker tracker;
  size_t seen = 0;
  for (int k = 1; k <= 40; ++k) {
    const SyntheticFrame f = scene.next();
    for (const Track& t : tracker.process(f.motion, f.segmentation).tracks) {
      EXPECT_TRUE(is_float32_exact(t)) << "frame " << k << " track " << t.id;
      ++seen;
    }
  }
  EXPECT_GT(seen, 40u);
}

TEST(TrackerScenario, OvertakingKeepsIdentitiesThroughMergeAndSplit) {
  // Lane 1 fast, lane 2 slow, 5.5 px apart: the boxes come within the merge gap for many frames.
  SceneOptions opts;
  opts.merge_close_objects = true;
  SyntheticScene scene({car(1, {60, 240}, {2.0, 0.0}), car(2, {120, 245.5}, {1.0, 0.0})}, drifting_camera(), opts);
  Tracker tracker;
  int merged_frames = 0;
  const auto count_merges = [&](int, std::vector<Region>& regions, const std::vector<TruthBox>& truth) {
    if (regions.size() == 1 && truth[0].visible && truth[1].visible) ++merged_frames;
  };
  scene.edit_regions = count_merges;
  const Score s = run_and_score(scene, tracker, run_for(170));
  ASSERT_GT(merged_frames, 15);  // the scenario really merges
  ASSERT_TRUE(s.track_ids_of_truth.count(1) && s.track_ids_of_truth.count(2));
  EXPECT_EQ(s.track_ids_of_truth.at(1).size(), 1u);
  EXPECT_EQ(s.track_ids_of_truth.at(2).size(), 1u);
  EXPECT_NE(s.track_ids_of_truth.at(1).front(), s.track_ids_of_truth.at(2).front());
  EXPECT_GT(s.matched, 0.95 * s.truth_instances);
  EXPECT_LT(s.mean_position_error, 1.0);
  EXPECT_EQ(s.all_confirmed_ids.size(), 2u);
}

TEST(TrackerScenario, PairAppearingMergedSplitsIntoTwoTracks) {
  // Two cars appear as one region (one track), then drive apart: the track keeps one of them, a new
  // track starts for the other, and both boxes shrink to the single cars quickly.
  SceneOptions opts;
  opts.merge_close_objects = true;
  SyntheticScene scene({car(1, {100, 240}, {1.6, 0.0}), car(2, {102, 245.5}, {1.0, 0.0})}, drifting_camera(), opts);
  Tracker tracker;
  int first_separate = 0;
  scene.edit_regions = [&](int frame, std::vector<Region>& regions, const std::vector<TruthBox>&) {
    if (regions.size() == 2 && first_separate == 0) first_separate = frame;
  };
  std::set<uint64_t> confirmed;
  for (int k = 1; k <= 120; ++k) {
    const SyntheticFrame f = scene.next();
    const TrackList out = tracker.process(f.motion, f.segmentation);
    for (const auto& t : out.tracks) {
      if (t.state == TrackState::Confirmed) confirmed.insert(t.id);
    }
    if (first_separate == 0 || k < first_separate + 15) continue;
    // Both cars matched, each by a car-sized box.
    for (const auto& truth : f.truth) {
      const Track* best = nullptr;
      for (const auto& t : out.tracks) {
        if (intersection_over_union(t.box, truth.box) > 0.5) best = &t;
      }
      ASSERT_NE(best, nullptr) << "car " << truth.id << " frame " << k;
      EXPECT_NEAR(best->box.width, truth.box.width, 1.0);
      EXPECT_NEAR(best->box.length, truth.box.length, 1.5);
    }
  }
  ASSERT_GT(first_separate, 10);
  EXPECT_EQ(confirmed.size(), 2u);
}

TEST(TrackerScenario, RegionSplitIntoTwoPiecesOfOneObjectStaysOneTrack) {
  SyntheticScene scene({car(1, {100, 200}, {1.5, 0.0})}, drifting_camera());
  // Frames 30-60: segmentation reports the car as its front and rear halves.
  scene.edit_regions = [](int frame, std::vector<Region>& regions, const std::vector<TruthBox>&) {
    if (frame < 30 || frame > 60 || regions.size() != 1) return;
    const double half = 0.45 * regions[0].box.length;
    regions = {piece_of(regions[0], 0.27, half), piece_of(regions[0], -0.27, half)};
  };
  Tracker tracker;
  const Score s = run_and_score(scene, tracker, run_for(90));
  EXPECT_EQ(s.all_confirmed_ids.size(), 1u);
  EXPECT_EQ(s.track_ids_of_truth.at(1).size(), 1u);
  EXPECT_EQ(s.matched, s.truth_instances);
  EXPECT_LT(s.mean_position_error, 0.6);
}

TEST(TrackerScenario, ObjectFragmentedFromItsFirstFrameEndsAsOneTrack) {
  // Segmentation reports the car as two halves for its first 12 frames (two tracks start), then whole.
  SyntheticScene scene({car(1, {100, 200}, {1.5, 0.0})}, drifting_camera());
  scene.edit_regions = [](int frame, std::vector<Region>& regions, const std::vector<TruthBox>&) {
    if (frame > 12 || regions.size() != 1) return;
    const double half = 0.45 * regions[0].box.length;
    regions = {piece_of(regions[0], 0.27, half), piece_of(regions[0], -0.27, half)};
  };
  Tracker tracker;
  RunOptions run = run_for(80);
  run.score_from_frame = 25;
  const Score s = run_and_score(scene, tracker, run);
  EXPECT_EQ(s.all_confirmed_ids.size(), 1u);
  EXPECT_EQ(s.matched, s.truth_instances);
  EXPECT_EQ(s.unmatched_confirmed_tracks, 0);
  EXPECT_LT(s.mean_length_error, 1.0);
}

TEST(TrackerScenario, ConvoyOfFourIsFourTracks) {
  std::vector<ObjectPath> convoy;
  for (int i = 0; i < 4; ++i) convoy.push_back(car(static_cast<uint64_t>(i + 1), {150.0 - 22.0 * i, 250}, {1.4, -0.5}));
  SyntheticScene scene(convoy, drifting_camera());
  Tracker tracker;
  const Score s = run_and_score(scene, tracker, run_for(120));
  EXPECT_EQ(s.all_confirmed_ids.size(), 4u);
  for (uint64_t id = 1; id <= 4; ++id) EXPECT_EQ(s.track_ids_of_truth.at(id).size(), 1u) << "vehicle " << id;
  EXPECT_EQ(s.matched, s.truth_instances);
  EXPECT_LT(s.mean_position_error, 0.5);
}

TEST(TrackerScenario, VehicleLeavingAndReenteringTheView) {
  // The camera pans right past the car and back: it leaves the view on the left and re-enters.
  const CameraPath pan = [](int frame) {
    const double shift = frame < 60 ? -6.0 * (frame - 1) : -6.0 * 59 + 6.0 * (frame - 60);
    return Homography(1, 0, shift, 0, 1, 0, 0, 0, 1);
  };
  SyntheticScene scene({car(1, {200, 240}, {1.0, 0.2})}, pan);
  Tracker tracker;
  std::vector<std::pair<int, uint64_t>> visible_ids;  // (frame, id) while visible
  for (int k = 1; k <= 130; ++k) {
    SyntheticFrame f = scene.next();
    f.motion.image_width = SceneOptions{}.image_width;  // as the motion layer reports it
    f.motion.image_height = SceneOptions{}.image_height;
    const TrackList out = tracker.process(f.motion, f.segmentation);
    for (const auto& t : out.tracks) {
      // Never a track far outside the view while nothing is there.
      if (!f.truth[0].visible && t.state == TrackState::Confirmed) {
        ADD_FAILURE() << "confirmed track without object at frame " << k;
      }
      if (t.state == TrackState::Confirmed && f.truth[0].visible) visible_ids.emplace_back(k, t.id);
    }
  }
  ASSERT_FALSE(visible_ids.empty());
  // Within each visible stretch the id never changes, and at most one track is confirmed per frame.
  for (size_t i = 1; i < visible_ids.size(); ++i) {
    if (visible_ids[i].first == visible_ids[i - 1].first + 1) {
      EXPECT_EQ(visible_ids[i].second, visible_ids[i - 1].second) << "frame " << visible_ids[i].first;
    }
    EXPECT_NE(visible_ids[i].first, visible_ids[i - 1].first);
  }
  // Tracked in both stretches.
  EXPECT_LT(visible_ids.front().first, 40);
  EXPECT_GT(visible_ids.back().first, 110);
}

// The first frame a car with one feature is reported confirmed, or 0.
int first_confirmed(const CameraPath& camera, cv::Point2d start, cv::Vec2d velocity, int quick_ground_frames) {
  ObjectPath o = car(1, start, velocity);
  o.feature_count = 1;
  SceneOptions scene_options;
  scene_options.seed = 2;  // its one feature lies inside the box (seed 1's is on its side edge)
  SyntheticScene scene({o}, camera, scene_options);
  TrackerOptions options;
  options.quick_confirm_max_ground_frames = quick_ground_frames;
  Tracker tracker(options);
  for (int k = 1; k <= 60; ++k) {
    SyntheticFrame f = scene.next();
    f.motion.image_width = SceneOptions{}.image_width;
    f.motion.image_height = SceneOptions{}.image_height;
    for (const auto& t : tracker.process(f.motion, f.segmentation).tracks) {
      if (t.state == TrackState::Confirmed) return k;
    }
  }
  return 0;
}

TEST(TrackerScenario, ACarTheFastCameraHasJustUncoveredConfirmsOnOneFeature) {
  // The camera sweeps 20 px per frame: new ground comes in at the right edge, and a car with one
  // feature comes in with it (in view from frame 6). On ground that has just come into view one
  // linked feature confirms with two region hits (TrackerOptions::quick_confirm_max_ground_frames).
  const CameraPath sweep = [](int frame) { return Homography(1, 0, -20.0 * (frame - 1), 0, 1, 0, 0, 0, 1); };
  const int quick = first_confirmed(sweep, {720, 240}, {1.0, 0.0}, 8);
  const int waiting = first_confirmed(sweep, {720, 240}, {1.0, 0.0}, -1);
  ASSERT_GT(quick, 0);
  EXPECT_LT(quick, waiting);
  // A still camera: the car drives in across the right edge (in view from frame 28), on ground long
  // in view: the track waits for a third hit either way.
  const int still = first_confirmed(static_camera(), {660, 240}, {-1.0, 0.0}, 8);
  EXPECT_GT(still, 20);
  EXPECT_EQ(still, first_confirmed(static_camera(), {660, 240}, {-1.0, 0.0}, -1));
}

TEST(TrackerScenario, TheImageSizeComesWithTheMotionEstimate) {
  // The motion estimate's size wins over TrackerOptions', which is the fallback for input without one.
  SceneOptions opts;
  opts.image_width = 300;
  opts.image_height = 200;
  auto reported_outside = [&](int options_width, int motion_width) {
    SyntheticScene scene({car(1, {200, 100}, {3.0, 0.0})}, static_camera(), opts);
    TrackerOptions o;
    o.image_width = options_width;
    o.image_height = opts.image_height;
    Tracker tracker(o);
    int outside = 0;
    for (int k = 1; k <= 60; ++k) {
      SyntheticFrame f = scene.next();
      f.motion.image_width = motion_width;
      f.motion.image_height = motion_width > 0 ? opts.image_height : 0;
      for (const auto& t : tracker.process(f.motion, f.segmentation).tracks) outside += t.box.cx > opts.image_width;
    }
    return outside;
  };
  EXPECT_EQ(reported_outside(0, opts.image_width), 0);      // from the motion estimate
  EXPECT_EQ(reported_outside(opts.image_width, 0), 0);      // the options' fallback
  EXPECT_EQ(reported_outside(1000, opts.image_width), 0);  // both known: the estimate's
  EXPECT_GT(reported_outside(1000, 0), 0);  // a wrong fallback lets it coast out of the real image
}

TEST(TrackerScenario, TrackLeavingTheImageIsNotReportedOutsideIt) {
  // Knowing the image size, a track is hidden as soon as its centre leaves the image, instead of
  // coasting outside it.
  SceneOptions opts;
  opts.image_width = 300;
  opts.image_height = 200;
  for (const bool image_known : {false, true}) {
    SyntheticScene scene({car(1, {200, 100}, {3.0, 0.0})}, static_camera(), opts);
    Tracker tracker;
    int outside_reported = 0;
    for (int k = 1; k <= 60; ++k) {
      SyntheticFrame f = scene.next();
      if (image_known) {  // the size comes with the motion estimate
        f.motion.image_width = opts.image_width;
        f.motion.image_height = opts.image_height;
      }
      for (const auto& t : tracker.process(f.motion, f.segmentation).tracks) {
        outside_reported += (t.box.cx > opts.image_width) ? 1 : 0;
      }
    }
    if (image_known) {
      EXPECT_EQ(outside_reported, 0);
    } else {
      EXPECT_GT(outside_reported, 0);  // without the image size it coasts out
    }
  }
}

TEST(TrackerScenario, StopAndGoKeepsItsIdentity) {
  // Drives 60 frames, stands still for 100 frames (4 s at 25 fps: no region, no moving feature), drives on.
  ObjectPath o;
  o.truth_id = 1;
  o.ground_centre = [](int frame) {
    const double v = 1.5;
    if (frame <= 60) return cv::Point2d(100 + v * (frame - 1), 200);
    if (frame <= 160) return cv::Point2d(100 + v * 59, 200);
    return cv::Point2d(100 + v * 59 + v * (frame - 160), 200);
  };
  o.heading_deg = [](int) { return 0.0; };
  SyntheticScene scene({o}, drifting_camera());
  Tracker tracker;
  const Score s = run_and_score(scene, tracker, run_for(230));
  ASSERT_TRUE(s.track_ids_of_truth.count(1));
  EXPECT_EQ(s.track_ids_of_truth.at(1).size(), 1u);
  EXPECT_EQ(s.all_confirmed_ids.size(), 1u);
  EXPECT_GT(s.matched, 0.95 * s.truth_instances);
}

// The direction of a box's longer side (a track may carry its box labelled either way round).
double long_axis_deg(const OrientedBox& box) { return box.length >= box.width ? box.angle_deg : box.angle_deg + 90.0; }

// A small car (8 x 3 px) with one feature, too few for a feature heading, whose regions' axes scatter
// by `blob_angle_noise_deg` (a blob a few pixels across). The mean error of its confirmed box's long
// axis over frames `from`..`to`, in degrees.
double one_feature_car_axis_error(std::function<cv::Point2d(int)> path, double blob_angle_noise_deg,
                                  const TrackerOptions& options, int from, int to) {
  ObjectPath o;
  o.truth_id = 1;
  o.length = 8.0;
  o.width = 3.0;
  o.feature_count = 1;
  o.ground_centre = std::move(path);
  SceneOptions blobs;
  blobs.region_angle_noise_deg = blob_angle_noise_deg;
  SyntheticScene scene({o}, drifting_camera(), blobs);
  Tracker tracker(options);
  double error = 0.0;
  int boxes = 0;
  for (int k = 1; k <= to; ++k) {
    const SyntheticFrame f = scene.next();
    const TrackList out = tracker.process(f.motion, f.segmentation);
    if (k < from) continue;
    for (const auto& t : out.tracks) {
      if (t.state != TrackState::Confirmed) continue;
      error += std::abs(axis_angle_difference_deg(long_axis_deg(t.box), long_axis_deg(f.truth[0].box)));
      ++boxes;
    }
  }
  return boxes > 0 ? error / boxes : 90.0;
}

// Slow (0.4 px/frame along 30 deg), blob axes scattered by 40 deg, frames 60-150.
double small_car_axis_error(const TrackerOptions& options) {
  const auto path = straight({200, 200}, {0.4 * std::cos(M_PI / 6.0), 0.4 * std::sin(M_PI / 6.0)});
  return one_feature_car_axis_error(path, 40.0, options, 60, 150);
}

TEST(TrackerScenario, ASmallCarWithoutFeatureHeadingTakesItsAxisFromItsTravel) {
  // Measured: 0.6 deg with the travel heading, 11.1 deg without.
  EXPECT_LT(small_car_axis_error(TrackerOptions{}), 3.0);
  TrackerOptions blob_axis_only;
  blob_axis_only.travel_heading_min_lengths = 0.0;
  EXPECT_GT(small_car_axis_error(blob_axis_only), 8.0);
}

// 0.5 px/frame along x for 50 frames, then a turn and along y; blob axes scattered by 10 deg; frames
// 70-110, while the travel still points back along the first leg.
double turning_car_axis_error(const TrackerOptions& options) {
  const auto path = [](int frame) {
    const double v = 0.5;
    if (frame <= 50) return cv::Point2d(200 + v * (frame - 1), 200);
    return cv::Point2d(200 + v * 49, 200 + v * (frame - 50));
  };
  return one_feature_car_axis_error(path, 10.0, options, 70, 110);
}

TEST(TrackerScenario, AfterABendTheTravelHeadingWaitsForTheTrackToAgree) {
  // Measured: 14.5 deg with the guard, 39.5 without it; 2.0 with no travel heading at all (the travel
  // still leans back along the first leg for a while: the price of the heading on straight roads).
  // With the travel from where the track started (travel_heading_max_lengths 0), 7.8: that chord
  // turns more slowly, so the guard holds it back for longer (docs/tracking.md, session 42).
  EXPECT_LT(turning_car_axis_error(TrackerOptions{}), 20.0);
  TrackerOptions no_guard;
  no_guard.travel_heading_max_turn_deg = 0.0;
  EXPECT_GT(turning_car_axis_error(no_guard), 30.0);
}

// 0.5 px/frame, heading 0 deg for 40 frames, turning steadily to -40 deg by frame 120, then straight;
// blob axes scattered by 10 deg; frames 140-220, on the straight after the bend.
double gently_turning_car_axis_error(const TrackerOptions& options) {
  const auto heading_deg = [](int frame) { return -40.0 * std::clamp((frame - 40) / 80.0, 0.0, 1.0); };
  return one_feature_car_axis_error(along_heading({150, 300}, 0.5, heading_deg), 10.0, options, 140, 220);
}

TEST(TrackerScenario, AfterAGentleBendTheTravelHeadingFollowsTheRoad) {
  // The turn never reaches travel_heading_max_turn_deg, so the guard above does not act. Measured:
  // 6.4 deg with the travel over the last two vehicle lengths, 17.3 with the travel from where the
  // track started (half the bend behind it for ever); 2.9 with no travel heading at all (blob axes
  // good to 10 deg need none).
  EXPECT_LT(gently_turning_car_axis_error(TrackerOptions{}), 9.0);
  TrackerOptions from_the_start;
  from_the_start.travel_heading_max_lengths = 0.0;
  EXPECT_GT(gently_turning_car_axis_error(from_the_start), 14.0);
}

// A car that drives 40 frames at 1.5 px/frame (13 m/s), brakes to a halt over 60 frames (5.5 m/s^2)
// and then stands (no region, no moving feature).
cv::Point2d halting_car(int frame) {
  const double v = 1.5, braking = 60.0, t = std::clamp(frame - 41.0, 0.0, braking);
  return cv::Point2d(100 + v * (std::min(frame, 41) - 1) + v * t - 0.5 * v / braking * t * t, 200);
}

// Frames after frame STANDING_FROM in which a confirmed track covers the car on PATH, over 200 frames.
int frames_reported_while_standing(const TrackerOptions& options, std::function<cv::Point2d(int)> path = halting_car,
                                   int standing_from = 100) {
  ObjectPath o;
  o.truth_id = 1;
  o.ground_centre = std::move(path);
  o.heading_deg = [](int) { return 0.0; };
  SyntheticScene scene({o}, drifting_camera());
  Tracker tracker(options);
  int reported = 0;
  for (int k = 1; k <= 200; ++k) {
    const SyntheticFrame f = scene.next();
    const TrackList out = tracker.process(f.motion, f.segmentation);
    if (k <= standing_from) continue;
    for (const auto& t : out.tracks) {
      const cv::Point2d d(t.box.cx - f.truth[0].box.cx, t.box.cy - f.truth[0].box.cy);
      if (t.state == TrackState::Confirmed && cv::norm(d) < 2.0) ++reported;
    }
  }
  return reported;
}

TEST(TrackerScenario, ACarThatHaltsStaysReportedWhileItStands) {
  // Its features, linked while it drove, are still tracked after it stops: they hold the track in place.
  EXPECT_EQ(frames_reported_while_standing(TrackerOptions{}), 100);
  TrackerOptions links_end_when_features_stop;
  links_end_when_features_stop.stopped_link_min_frames = 0;
  EXPECT_LT(frames_reported_while_standing(links_end_when_features_stop), 10);
}

TEST(TrackerScenario, AParkedCarNudgedForAMomentIsNotHeldWhileItStands) {
  // It moves 0.3 px/frame (2.6 m/s) for 20 frames, 6 px or 0.47 car lengths at 0.35 m/px (a parked
  // car's corner dragged along by a passing one looks so), and stands from frame 21: confirmed and
  // linked long enough to be held, but it has not gone 0.6 car lengths.
  const auto nudged = [](int frame) { return cv::Point2d(100 + 0.3 * (std::min(frame, 21) - 1), 200); };
  const int held = frames_reported_while_standing(TrackerOptions{}, nudged, 40);
  TrackerOptions without_travel;
  without_travel.stopped_link_min_travel_lengths = 0.0;
  const int held_without = frames_reported_while_standing(without_travel, nudged, 40);
  std::printf("nudged parked car, frames 41-200 reported: %d (without the travel check: %d)\n", held, held_without);
  EXPECT_GT(held_without, 150) << "the scene must hold the track without the check, or the test shows nothing";
  EXPECT_LT(held, 5);
}

// A road-grey car: segmentation finds only its windscreen (the front 40 %) from its first frame, while
// its features sit all along it.
Score car_seen_by_its_windscreen(const TrackerOptions& options) {
  SyntheticScene scene({car(1, {100, 200}, {1.5, 0.4})}, drifting_camera());
  scene.edit_regions = [](int, std::vector<Region>& regions, const std::vector<TruthBox>&) {
    if (regions.size() == 1) regions = {piece_of(regions[0], 0.3, 0.4 * regions[0].box.length)};
  };
  Tracker tracker(options);
  RunOptions run = run_for(120);
  run.score_from_frame = 40;
  return run_and_score(scene, tracker, run);
}

TEST(TrackerScenario, ACarSeenOnlyByItsWindscreenKeepsItsLength) {
  const Score s = car_seen_by_its_windscreen(TrackerOptions{});
  TrackerOptions blob_only;
  blob_only.feature_span_margin_px = -1.0;
  blob_only.link_min_length_factor = 0.0;
  const Score b = car_seen_by_its_windscreen(blob_only);
  TrackerOptions links_in_the_prediction_only;
  links_in_the_prediction_only.link_min_length_factor = 0.0;
  const Score p = car_seen_by_its_windscreen(links_in_the_prediction_only);
  std::printf("windscreen only: length error %.2f px, position %.2f px (links in the prediction only: %.2f, %.2f; "
              "from the blob alone: %.2f, %.2f)\n",
              s.mean_length_error, s.mean_position_error, p.mean_length_error, p.mean_position_error,
              b.mean_length_error, b.mean_position_error);
  EXPECT_EQ(s.matched, s.truth_instances);
  EXPECT_LT(s.mean_length_error, 3.0);
  EXPECT_GT(p.mean_length_error, s.mean_length_error + 1.0);
  EXPECT_GT(b.mean_length_error, 6.0);
}

TEST(TrackerScenario, BusyRoadWithMissesAndClutter) {
  // Two lanes each way, twelve cars overtaking each other (merged regions while close), 10 % of
  // regions missed, three false regions per frame, the hovering camera.
  std::vector<ObjectPath> cars;
  for (int i = 0; i < 6; ++i) {
    cars.push_back(car(static_cast<uint64_t>(i + 1), {40.0 + 35.0 * i, 200.0 + 6.0 * (i % 2)}, {1.2 + 0.25 * (i % 3), 0.0}));
    cars.push_back(car(static_cast<uint64_t>(i + 7), {600.0 - 35.0 * i, 225.0 + 6.0 * (i % 2)}, {-1.0 - 0.3 * (i % 3), 0.0}));
  }
  SceneOptions opts;
  opts.merge_close_objects = true;
  opts.region_miss_probability = 0.1;
  opts.clutter_regions_per_frame = 3;
  SyntheticScene scene(cars, drifting_camera(), opts);
  int merged = 0;
  scene.edit_regions = [&](int, std::vector<Region>& regions, const std::vector<TruthBox>& truth) {
    int moving = 0;
    for (const auto& t : truth) moving += (t.visible && t.moving) ? 1 : 0;
    if (static_cast<int>(regions.size()) - 3 < moving - 2) ++merged;  // clearly fewer regions than cars
  };
  Tracker tracker;
  const Score s = run_and_score(scene, tracker, run_for(200));
  EXPECT_GT(merged, 10);
  EXPECT_GT(s.matched, 0.95 * s.truth_instances) << s.matched << " of " << s.truth_instances;
  EXPECT_LT(s.mean_position_error, 1.0);
  EXPECT_LT(s.mean_width_error, 1.0);
  EXPECT_LT(s.mean_length_error, 1.5);
  int switches = 0;
  for (const auto& [truth, ids] : s.track_ids_of_truth) switches += static_cast<int>(ids.size()) - 1;
  EXPECT_LE(switches, 1);
  EXPECT_LT(s.unmatched_confirmed_tracks, s.matched / 100);  // clutter never confirms
}

TEST(TrackerScenario, ParkedVehicleGetsNoTrack) {
  ObjectPath parked;
  parked.truth_id = 1;
  parked.ground_centre = [](int) { return cv::Point2d(300, 200); };
  parked.heading_deg = [](int) { return 30.0; };
  SyntheticScene scene({parked}, drifting_camera());
  Tracker tracker;
  for (int k = 1; k <= 60; ++k) {
    const SyntheticFrame f = scene.next();
    EXPECT_TRUE(tracker.process(f.motion, f.segmentation).tracks.empty());
  }
}

TEST(TrackerScenario, AngleWrapAroundKeepsAStableBox) {
  // Heading ~90 deg: region angles jitter across +-90 (e.g. 89.2, -89.5), which is the same axis.
  ObjectPath o;
  o.truth_id = 1;
  o.ground_centre = straight({300, 100}, {0.0, 1.5});
  o.heading_deg = [](int) { return 90.0; };
  SceneOptions opts;
  opts.region_angle_noise_deg = 2.0;
  SyntheticScene scene({o}, static_camera(), opts);
  Tracker tracker;
  int wrapped = 0;
  scene.edit_regions = [&](int, std::vector<Region>& regions, const std::vector<TruthBox>&) {
    for (const auto& r : regions) wrapped += r.box.angle_deg < 0.0 ? 1 : 0;
  };
  for (int k = 1; k <= 150; ++k) {
    const SyntheticFrame f = scene.next();
    const TrackList out = tracker.process(f.motion, f.segmentation);
    if (k < 10) continue;
    ASSERT_EQ(out.tracks.size(), 1u) << "frame " << k;
    const Track& t = out.tracks[0];
    EXPECT_LT(std::abs(axis_angle_difference_deg(t.box.angle_deg, 90.0)), 2.0) << "frame " << k;
    EXPECT_NEAR(t.box.length, 15.0, 0.8);
    EXPECT_NEAR(t.box.width, 5.0, 0.8);
    EXPECT_GT(t.box.angle_deg, -90.0);
    EXPECT_LE(t.box.angle_deg, 90.0);
  }
  EXPECT_GT(wrapped, 20);  // the jitter really crosses the wrap
}

}  // namespace
}  // namespace uavmot::tracking::testing

namespace uavmot::tracking::testing {
namespace {

TEST(TrackerScenario, OncomingVehicleDoesNotInheritAStoppedVehiclesId) {
  // Car 1 drives right and stops (no region); car 2, parked right beside that spot, drives off to the
  // left while car 1 stands: it must get a new id, and car 1 its old one when it drives on.
  ObjectPath stopper;
  stopper.truth_id = 1;
  stopper.ground_centre = [](int frame) {
    if (frame <= 40) return cv::Point2d(100 + 1.5 * (frame - 1), 200);
    if (frame <= 140) return cv::Point2d(100 + 1.5 * 39, 200);
    return cv::Point2d(100 + 1.5 * 39 + 1.5 * (frame - 140), 200);
  };
  stopper.heading_deg = [](int) { return 0.0; };
  ObjectPath oncoming;
  oncoming.truth_id = 2;
  oncoming.ground_centre = [](int frame) {
    return frame <= 80 ? cv::Point2d(164, 201) : cv::Point2d(164 - 1.5 * (frame - 80), 201);
  };
  oncoming.heading_deg = [](int) { return 0.0; };
  SyntheticScene scene({stopper, oncoming}, static_camera());
  Tracker tracker;
  const Score s = run_and_score(scene, tracker, run_for(180));
  ASSERT_TRUE(s.track_ids_of_truth.count(1) && s.track_ids_of_truth.count(2));
  EXPECT_EQ(s.track_ids_of_truth.at(1).size(), 1u);
  EXPECT_EQ(s.track_ids_of_truth.at(2).size(), 1u);
  EXPECT_NE(s.track_ids_of_truth.at(1).front(), s.track_ids_of_truth.at(2).front());
}

}  // namespace
}  // namespace uavmot::tracking::testing
