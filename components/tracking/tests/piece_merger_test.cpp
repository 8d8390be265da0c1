// Pieces of one long vehicle (piece_merger.hpp): the geometric rule, and the tracker ending with one
// track on a truck that segmentation reports as cab and trailer.
#include <set>

#include <gtest/gtest.h>

#include "synthetic_scene.hpp"
#include "piece_merger.hpp"

namespace uavmot::tracking::testing {
namespace {

// At the default scene (0.35 m/px, 25 fps) 1 px/frame is 8.75 m/s, a car is 12.9 x 5.1 px.
const SceneInfo kScene;
const TrackerOptions kOptions;

// A box of `length` along the x axis whose rear end is at `rear_x`.
OrientedBox along_x(double rear_x, double length, double width = 7.0, double y = 100.0, double angle = 0.0) {
  return {rear_x + length / 2.0, y, width, length, angle};
}

TEST(PieceMerger, CabAndTrailerNoseToTailArePieces) {
  const OrientedBox trailer = along_x(100.0, 20.0), cab = along_x(121.0, 9.0);  // 1 px gap
  EXPECT_TRUE(are_pieces_of_one_object(trailer, {1.0, 0.0}, cab, {1.02, 0.01}, kOptions, kScene));
  EXPECT_TRUE(are_pieces_of_one_object(cab, {1.02, 0.01}, trailer, {1.0, 0.0}, kOptions, kScene));
}

TEST(PieceMerger, ANearSquareCabWithANoisyAngleIsStillAPiece) {
  // The direction of travel, not the cab box's angle, says where "behind" is.
  const OrientedBox trailer = along_x(100.0, 20.0), cab = along_x(121.0, 8.0, 7.0, 100.0, 35.0);
  EXPECT_TRUE(are_pieces_of_one_object(trailer, {1.0, 0.0}, cab, {1.0, 0.0}, kOptions, kScene));
}

TEST(PieceMerger, CarsKeepingADistanceAreNotPieces) {
  // 2.5 m between bumpers at speed: two cars.
  const OrientedBox a = along_x(100.0, 13.0, 5.0), b = along_x(113.0 + 2.5 / kScene.gsd_m, 13.0, 5.0);
  EXPECT_FALSE(are_pieces_of_one_object(a, {1.0, 0.0}, b, {1.0, 0.0}, kOptions, kScene));
}

TEST(PieceMerger, TheEndsOfAUniformTrailerUpTo2mApartArePieces) {
  // A bright, uniform trailer roof has no gradient inside: segmentation reports the blobs at its
  // ends, 1.9 m apart on `paper` seed 101's 11 m truck. 1.5 m (the old default) left them two tracks.
  const OrientedBox rear = along_x(100.0, 15.0, 7.0), cab = along_x(115.0 + 1.9 / kScene.gsd_m, 5.0, 8.5);
  EXPECT_TRUE(are_pieces_of_one_object(rear, {1.0, 0.0}, cab, {1.0, 0.0}, kOptions, kScene));
  TrackerOptions old_gap = kOptions;
  old_gap.piece_max_gap_m = 1.5;
  EXPECT_FALSE(are_pieces_of_one_object(rear, {1.0, 0.0}, cab, {1.0, 0.0}, old_gap, kScene));
}

TEST(PieceMerger, CarsSideBySideOrInTheNextLaneAreNotPieces) {
  const OrientedBox a = along_x(100.0, 13.0, 5.0), beside = along_x(100.0, 13.0, 5.0, 106.0);
  const OrientedBox next_lane_ahead = along_x(113.5, 13.0, 5.0, 110.0);
  EXPECT_FALSE(are_pieces_of_one_object(a, {1.0, 0.0}, beside, {1.0, 0.0}, kOptions, kScene));
  EXPECT_FALSE(are_pieces_of_one_object(a, {1.0, 0.0}, next_lane_ahead, {1.0, 0.0}, kOptions, kScene));
}

TEST(PieceMerger, ABoxOverTwoCarsSideBySideIsNoPiece) {
  // Segmentation merged two cars driving side by side into one wide box; the car ahead is not part of it.
  const OrientedBox pair = along_x(100.0, 13.0, 14.0), ahead = along_x(113.5, 13.0, 5.0, 102.0);
  EXPECT_FALSE(are_pieces_of_one_object(pair, {1.0, 0.0}, ahead, {1.0, 0.0}, kOptions, kScene));
  TrackerOptions any_width = kOptions;  // the width limit is what decides here
  any_width.max_object_width_m = 100.0;
  EXPECT_TRUE(are_pieces_of_one_object(pair, {1.0, 0.0}, ahead, {1.0, 0.0}, any_width, kScene));
}

TEST(PieceMerger, ACrawlingQueueIsNotMerged) {
  // Bumper to bumper is normal in a queue: below piece_min_speed_mps nothing is merged.
  const OrientedBox a = along_x(100.0, 13.0, 5.0), b = along_x(113.5, 13.0, 5.0);
  const double crawl = 0.9 * kOptions.piece_min_speed_mps / (kScene.gsd_m * kScene.fps);  // px/frame
  EXPECT_FALSE(are_pieces_of_one_object(a, {crawl, 0.0}, b, {crawl, 0.0}, kOptions, kScene));
  EXPECT_TRUE(are_pieces_of_one_object(a, {1.0, 0.0}, b, {1.0, 0.0}, kOptions, kScene));
}

TEST(PieceMerger, DifferentMotionOrTooLongIsNotOneObject) {
  const OrientedBox a = along_x(100.0, 13.0, 5.0), b = along_x(113.5, 13.0, 5.0);
  EXPECT_FALSE(are_pieces_of_one_object(a, {1.0, 0.0}, b, {2.0, 0.0}, kOptions, kScene));  // overtaking
  const OrientedBox long_a = along_x(100.0, 25.0), long_b = along_x(125.5, 25.0);  // 50 px > 3 car lengths
  EXPECT_FALSE(are_pieces_of_one_object(long_a, {1.0, 0.0}, long_b, {1.0, 0.0}, kOptions, kScene));
}

TEST(PieceMerger, TheEndsOfATruckInABendArePiecesACarClosingInIsNot) {
  // `paper` seed 106's 11 m truck turning at 16 deg/s: its rear piece's features move 0.18 px/frame
  // (1.6 m/s) across the line to its cab's, 16 px ahead, and 0.01 along it. A rigid body turning
  // keeps its points' distances, so that difference lies across the line.
  const OrientedBox rear = along_x(100.0, 12.0, 8.0), cab = along_x(114.5, 15.0, 8.0);  // centres 16 px apart
  const cv::Vec2d rear_motion(0.78, 0.06), cab_motion(0.78, -0.12);
  EXPECT_TRUE(pieces_move_as_one_body(rear, rear_motion, cab, cab_motion, kOptions, kScene));
  EXPECT_TRUE(are_pieces_of_one_object(rear, rear_motion, cab, cab_motion, kOptions, kScene));
  TrackerOptions no_turn = kOptions;
  no_turn.piece_max_turn_rate_dps = 0.0;
  EXPECT_FALSE(are_pieces_of_one_object(rear, rear_motion, cab, cab_motion, no_turn, kScene));
  // The same speed difference along the line is a car closing in on the one ahead.
  EXPECT_FALSE(pieces_move_as_one_body(rear, {0.96, 0.0}, cab, {0.78, 0.0}, kOptions, kScene));
  // A turn faster than any vehicle's is no turn: 0.6 px/frame across 16 px is 54 deg/s.
  EXPECT_FALSE(pieces_move_as_one_body(rear, {0.78, 0.3}, cab, {0.78, -0.3}, kOptions, kScene));
}

TEST(PieceMerger, DisabledByAZeroGap) {
  TrackerOptions off = kOptions;
  off.piece_max_gap_m = 0.0;
  EXPECT_FALSE(are_pieces_of_one_object(along_x(100.0, 20.0), {1.0, 0.0}, along_x(121.0, 9.0), {1.0, 0.0}, off, kScene));
}

// A 32 x 7 px truck that segmentation always reports as a 21 px trailer and a 9 px cab, 2 px apart.
SyntheticScene truck_in_two_pieces() {
  ObjectPath truck;
  truck.truth_id = 1;
  truck.length = 32.0;
  truck.width = 7.0;
  truck.ground_centre = straight({120, 240}, {1.2, 0.3});
  truck.feature_count = 12;
  SyntheticScene scene({truck}, static_camera());
  scene.edit_regions = [](int, std::vector<Region>& regions, const std::vector<TruthBox>&) {
    if (regions.size() != 1) return;
    regions = {piece_of(regions[0], -(16.0 - 10.5) / 32.0, 21.0), piece_of(regions[0], (16.0 - 4.5) / 32.0, 9.0)};
  };
  return scene;
}

TEST(PieceMerger, TruckReportedAsCabAndTrailerEndsAsOneTrackOfItsFullLength) {
  SyntheticScene scene = truck_in_two_pieces();
  Tracker tracker;
  RunOptions run = run_for(100);
  run.score_from_frame = 20;
  const Score s = run_and_score(scene, tracker, run);
  EXPECT_EQ(s.track_ids_of_truth.at(1).size(), 1u);
  EXPECT_EQ(s.matched, s.truth_instances);
  EXPECT_EQ(s.unmatched_confirmed_tracks, 0);
  EXPECT_LT(s.mean_length_error, 2.0);
}

TEST(PieceMerger, WithoutTheRuleTheTruckStaysTwoTracks) {
  // The scenario above is a real test of the rule: switched off, cab and trailer keep their tracks.
  SyntheticScene scene = truck_in_two_pieces();
  TrackerOptions options;
  options.piece_max_gap_m = 0.0;
  Tracker tracker(options);
  RunOptions run = run_for(100);
  run.score_from_frame = 20;
  const Score s = run_and_score(scene, tracker, run);
  EXPECT_GE(s.all_confirmed_ids.size(), 2u);
  EXPECT_GT(s.mean_length_error, 5.0);
}

// The truck above, in two pieces 5 px apart (a uniform roof between them), turning at 0.8 deg/frame
// (20 deg/s) at 0.8 px/frame (7 m/s) from its first frame on; the ids of its confirmed tracks from
// frame 10. Only the piece merger may join the pieces: the shared-region rule
// (single_object_size_factor) is off, and the features' velocities are exact to 0.01 px/frame, so
// the median over each piece stays what the turn makes it (0.16-0.19 px/frame apart across the
// line between the pieces, 1.4-1.6 m/s, as on `paper` seed 106).
std::set<uint64_t> confirmed_ids_of_turning_truck(TrackerOptions options) {
  options.single_object_size_factor = 0.0;
  const auto heading_deg = [](int frame) { return -0.8 * frame; };
  ObjectPath truck;
  truck.truth_id = 1;
  truck.length = 32.0;
  truck.width = 7.0;
  truck.feature_count = 12;
  truck.heading_deg = heading_deg;
  truck.ground_centre = along_heading({120, 300}, 0.8, heading_deg);
  SceneOptions precise;
  precise.feature_velocity_noise = 0.01;
  SyntheticScene scene({truck}, static_camera(), precise);
  scene.edit_regions = [](int, std::vector<Region>& regions, const std::vector<TruthBox>&) {
    if (regions.size() != 1) return;
    regions = {piece_of(regions[0], -(16.0 - 9.0) / 32.0, 18.0), piece_of(regions[0], (16.0 - 4.5) / 32.0, 9.0)};
  };
  Tracker tracker(options);
  return run_and_score(scene, tracker, run_for(100)).all_confirmed_ids;
}

TEST(PieceMerger, ATruckInABendEndsAsOneTrack) {
  // Without the turn allowance the two pieces never pass as one body.
  EXPECT_EQ(confirmed_ids_of_turning_truck(TrackerOptions{}).size(), 1u);
  TrackerOptions no_turn;
  no_turn.piece_max_turn_rate_dps = 0.0;
  EXPECT_GE(confirmed_ids_of_turning_truck(no_turn).size(), 2u);
}

TEST(PieceMerger, AFeaturelessCabIsMergedOnceItsFilterHasSettled) {
  // No feature is found on the cab (a dark, uniform roof): its motion comes from its own track's
  // filter once that has 10 region hits, so cab and trailer still end as one track.
  SyntheticScene scene = truck_in_two_pieces();
  Tracker tracker;
  RunOptions run = run_for(100);
  run.score_from_frame = 30;
  const cv::Vec2d velocity(1.2, 0.3);
  const cv::Point2d axis = cv::Point2d(velocity[0], velocity[1]) / cv::norm(velocity);
  run.edit_motion = [&](MotionEstimate& motion) {
    const cv::Point2d centre = cv::Point2d(120, 240) + cv::Point2d(velocity[0], velocity[1]) * (motion.frame_index - 1.0);
    std::erase_if(motion.features, [&](const TrackedFeature& f) { return (f.position - centre).dot(axis) > 6.0; });
  };
  const Score s = run_and_score(scene, tracker, run);
  EXPECT_EQ(s.matched, s.truth_instances);
  EXPECT_EQ(s.unmatched_confirmed_tracks, 0);
  EXPECT_LT(s.mean_length_error, 2.0);
}

}  // namespace
}  // namespace uavmot::tracking::testing
