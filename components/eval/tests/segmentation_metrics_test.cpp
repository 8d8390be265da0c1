// Paper Tables I and II and the false alarms on a hand-made frame (answers worked out by hand).
#include <gtest/gtest.h>

#include "eval_test_helpers.hpp"

namespace uavmot::eval {
namespace {
using testing::object;
using testing::oriented;

// Frame 1: moving cars A, B, C, D, F (10 px long, 4 px wide, along x), parked car E.
Sequence hand_sequence() {
  Sequence s = testing::empty_sequence(1, 0.5);
  s.objects[1] = {object(1, 10, 10, 4, 10), object(2, 30, 10, 4, 10), object(3, 42, 10, 4, 10), object(4, 70, 10, 4, 10),
                  object(5, 90, 10, 4, 10, 0, false, true), object(6, 110, 10, 4, 10)};
  return s;
}

Predictions hand_predictions() {
  Predictions p;
  p.boxes[1] = {
      oriented(-1, 10.5, 9.75, 5, 11),  // A: correct, off by (0.5, 0.25), 1 px too wide and too long
      oriented(-1, 36, 10, 4, 22),      // B and C in one box: under-segmented, two mistakes
      oriented(-1, 67.5, 10, 4, 5),     // D in two halves: over-segmented, one mistake
      oriented(-1, 72.5, 10, 4, 5),
      oriented(-1, 90, 10, 4, 10),      // on the parked car E: a false alarm on a parked vehicle
      oriented(-1, 200, 200, 4, 10),    // on nothing: a false alarm
  };                                    // F: missed
  return p;
}

TEST(Completeness, CountsCorrectMergedSplitAndMissedAsThePaper) {
  const EvaluationResult r = evaluate(hand_sequence(), hand_predictions());
  EXPECT_EQ(r.completeness.instances, 5);
  EXPECT_EQ(r.completeness.correct, 1);
  EXPECT_EQ(r.completeness.under_segmented, 2);  // two merged objects are two mistakes
  EXPECT_EQ(r.completeness.over_segmented, 1);   // one object in two segments is one mistake
  EXPECT_EQ(r.completeness.missed, 1);
  EXPECT_DOUBLE_EQ(r.completeness.correct_rate(), 0.2);
}

// The same instances by apparent length: a 6 px car missed, a 14 px car found, a 30 px truck found
// (bands < 10, 10-20, >= 20 px), and the bands add up to the totals.
TEST(Completeness, CountsEachBandOfApparentLength) {
  Sequence s = testing::empty_sequence(1, 0.5);
  s.objects[1] = {object(1, 10, 10, 3, 6), object(2, 40, 10, 5, 14), object(3, 80, 10, 5, 30)};
  Predictions p;
  p.boxes[1] = {oriented(-1, 40, 10, 5, 14), oriented(-1, 80, 10, 5, 30)};
  const EvaluationResult r = evaluate(s, p);
  ASSERT_EQ(r.completeness.by_length.size(), 3u);
  const auto& small = r.completeness.by_length[0];
  const auto& medium = r.completeness.by_length[1];
  const auto& large = r.completeness.by_length[2];
  EXPECT_EQ(small.instances, 1);
  EXPECT_EQ(small.missed, 1);
  EXPECT_EQ(small.correct, 0);
  EXPECT_EQ(medium.instances, 1);
  EXPECT_EQ(medium.correct, 1);
  EXPECT_EQ(large.instances, 1);
  EXPECT_EQ(large.correct, 1);
  EXPECT_DOUBLE_EQ(large.correct_rate(), 1.0);
  // The hand frame: five 10 px cars, all in the middle band, which repeats the totals.
  const EvaluationResult h = evaluate(hand_sequence(), hand_predictions());
  EXPECT_EQ(h.completeness.by_length[0].instances, 0);
  EXPECT_EQ(h.completeness.by_length[1].instances, h.completeness.instances);
  EXPECT_EQ(h.completeness.by_length[1].correct, h.completeness.correct);
  EXPECT_EQ(h.completeness.by_length[1].missed, h.completeness.missed);
}

TEST(Precision, MeanAbsoluteErrorsOverCorrectInstancesInPixelsAndMetres) {
  const EvaluationResult r = evaluate(hand_sequence(), hand_predictions());
  EXPECT_EQ(r.precision.samples, 1);
  EXPECT_TRUE(r.precision.oriented);
  EXPECT_NEAR(r.precision.error_x_px, 0.5, 1e-12);
  EXPECT_NEAR(r.precision.error_y_px, 0.25, 1e-12);
  EXPECT_NEAR(r.precision.error_width_px, 1.0, 1e-12);
  EXPECT_NEAR(r.precision.error_length_px, 1.0, 1e-12);
  EXPECT_NEAR(r.precision.error_x_m, 0.25, 1e-12);  // GSD 0.5 m/px
  EXPECT_NEAR(r.precision.error_length_m, 0.5, 1e-12);
}

TEST(Precision, AveragesOverSeveralCorrectInstancesAndHandlesTurnedBoxes) {
  Sequence s = testing::empty_sequence(2, 0.0);
  s.objects[1] = {object(1, 50, 50, 4, 12, 30.0)};
  s.objects[2] = {object(1, 52, 51, 4, 12, 30.0)};
  Predictions p;
  // A box given with the opposite axis direction is the same box: angle 210 == 30.
  p.boxes[1] = {oriented(1, 51, 50, 4, 12, normalize_axis_angle_deg(210.0))};
  p.boxes[2] = {oriented(1, 52, 53, 6, 12, 30.0)};
  const EvaluationResult r = evaluate(s, p);
  EXPECT_EQ(r.completeness.correct, 2);
  EXPECT_NEAR(r.precision.error_x_px, 0.5, 1e-12);   // (1 + 0) / 2
  EXPECT_NEAR(r.precision.error_y_px, 1.0, 1e-12);   // (0 + 2) / 2
  EXPECT_NEAR(r.precision.error_width_px, 1.0, 1e-12);  // (0 + 2) / 2
  EXPECT_NEAR(r.precision.error_length_px, 0.0, 1e-12);
  EXPECT_DOUBLE_EQ(r.precision.error_x_m, 0.0);  // GSD unknown
}

TEST(FalseAlarms, CountsBoxesOnNoMovingObjectAndThoseOnParkedVehicles) {
  const EvaluationResult r = evaluate(hand_sequence(), hand_predictions());
  EXPECT_EQ(r.false_alarms.boxes, 6);
  EXPECT_EQ(r.false_alarms.false_alarms, 2);
  EXPECT_EQ(r.false_alarms.on_parked, 1);
  EXPECT_EQ(r.false_alarms.frames, 1);
  EXPECT_DOUBLE_EQ(r.false_alarms.per_frame(), 2.0);
}

TEST(FalseAlarms, BoxesOnStoppedVehiclesAreNeitherHitsNorFalseAlarms) {
  Sequence s = testing::empty_sequence(1);
  s.objects[1] = {object(1, 10, 10, 4, 10, 0, /*moving=*/false, /*parked=*/false)};
  Predictions p;
  p.boxes[1] = {oriented(-1, 10, 10, 4, 10)};
  const EvaluationResult r = evaluate(s, p);
  EXPECT_EQ(r.completeness.instances, 0);
  EXPECT_EQ(r.false_alarms.false_alarms, 0);
  EXPECT_EQ(r.false_alarms.on_stopped, 1);
}

TEST(Completeness, ObjectsMostlyOutsideTheImageAreNotScored) {
  Sequence s = testing::empty_sequence(1);
  s.objects[1] = {object(1, 1, 10, 4, 10, 0, true, false, /*visibility=*/0.4), object(2, 50, 10, 4, 10)};
  const EvaluationResult r = evaluate(s, Predictions{});
  EXPECT_EQ(r.completeness.instances, 1);
  EXPECT_EQ(r.completeness.missed, 1);
  EvalOptions all;
  all.min_visibility = 0.0;
  EXPECT_EQ(evaluate(s, Predictions{}, all).completeness.missed, 2);
}

TEST(Completeness, SmallFragmentLyingOnTheObjectStillCountsAsASegment) {
  Sequence s = testing::empty_sequence(1);
  s.objects[1] = {object(1, 10, 10, 4, 10)};
  Predictions p;
  // 4 px of a 10 px car: covers 40 % (< 50 %) but lies entirely on it.
  p.boxes[1] = {oriented(-1, 7, 10, 4, 4), oriented(-1, 12.5, 10, 4, 5)};
  const EvaluationResult r = evaluate(s, p);
  EXPECT_EQ(r.completeness.over_segmented, 1);
  EXPECT_EQ(r.false_alarms.false_alarms, 0);
}

TEST(Completeness, FrameRangeLimitsTheScoredFrames) {
  Sequence s = testing::empty_sequence(3);
  for (int64_t f = 1; f <= 3; ++f) s.objects[f] = {object(1, 10, 10, 4, 10)};
  Predictions p;
  p.boxes[2] = {oriented(1, 10, 10, 4, 10)};
  EvalOptions options;
  options.first_frame = 2;
  options.last_frame = 2;
  const EvaluationResult r = evaluate(s, p, options);
  EXPECT_EQ(r.frames, 1);
  EXPECT_EQ(r.completeness.instances, 1);
  EXPECT_EQ(r.completeness.correct, 1);
}

TEST(Evaluate, RejectsBadOptions) {
  EvalOptions bad;
  bad.min_object_coverage = 1.5;
  EXPECT_THROW(evaluate(testing::empty_sequence(1), Predictions{}, bad), InvalidArgument);
  EvalOptions bad_iou;
  bad_iou.iou_thresholds = {0.0};
  EXPECT_THROW(evaluate(testing::empty_sequence(1), Predictions{}, bad_iou), InvalidArgument);
}

}  // namespace
}  // namespace uavmot::eval

namespace uavmot::eval {
namespace {

TEST(Predictions, RegionsOfOneMethodAndClustersFromASegmentationResult) {
  SegmentationResult seg;
  seg.frame_index = 1;
  seg.regions = {{OrientedBox{10, 10, 4, 10, 0}, SegmentationMethod::Fusion, 1.0, -1},
                 {OrientedBox{30, 10, 4, 10, 0}, SegmentationMethod::Korn, 1.0, -1},
                 {OrientedBox{50, 10, 4, 10, 0}, SegmentationMethod::Fusion, 1.0, -1}};
  FeatureCluster cluster;
  cluster.box = OrientedBox{20, 10, 4, 30, 0};
  seg.clusters = {cluster};
  Predictions fusion, clusters;
  fusion.add_regions(seg, SegmentationMethod::Fusion);
  clusters.add_clusters(seg);
  ASSERT_EQ(fusion.boxes.at(1).size(), 2u);
  EXPECT_DOUBLE_EQ(fusion.boxes.at(1)[1].oriented->cx, 50.0);
  EXPECT_EQ(fusion.boxes.at(1)[0].id, -1);
  EXPECT_FALSE(fusion.has_identities());
  ASSERT_EQ(clusters.boxes.at(1).size(), 1u);
}

}  // namespace
}  // namespace uavmot::eval
