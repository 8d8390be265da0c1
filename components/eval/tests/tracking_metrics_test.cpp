// CLEAR MOT, IDF1 and HOTA on hand-made tracks; the expected values are worked out by hand
// following TrackEval's definitions (comments show the arithmetic).
#include <cmath>

#include <gtest/gtest.h>

#include "eval_test_helpers.hpp"

namespace uavmot::eval {
namespace {
using testing::object;
using testing::oriented;

// Objects 1 (x = 10) and 2 (x = 50) in frames 1..5.
// Track 3 follows object 1 but misses frame 3; track 4 follows object 2 in frames 1-3 and
// track 5 takes over in frames 4-5 (an identity switch); track 9 is a false positive in frame 1.
struct Case {
  Sequence sequence = testing::empty_sequence(5);
  Predictions predictions;
  Case() {
    for (int64_t f = 1; f <= 5; ++f) {
      sequence.objects[f] = {object(1, 10, 10, 4, 10), object(2, 50, 10, 4, 10)};
      auto& boxes = predictions.boxes[f];
      if (f != 3) boxes.push_back(oriented(3, 10, 10, 4, 10));
      boxes.push_back(oriented(f <= 3 ? 4 : 5, 50, 10, 4, 10));
      if (f == 1) boxes.push_back(oriented(9, 200, 100, 4, 10));
    }
  }
};

TEST(ClearMot, CountsTheSwitchTheMissTheFalsePositiveAndTheFragment) {
  Case c;
  const EvaluationResult r = evaluate(c.sequence, c.predictions);
  ASSERT_EQ(r.tracking.size(), 2u);
  const ClearMot& m = r.tracking[0];
  EXPECT_DOUBLE_EQ(m.threshold, 0.5);
  EXPECT_EQ(m.gt_detections, 10);
  EXPECT_EQ(m.tp, 9);
  EXPECT_EQ(m.fn, 1);
  EXPECT_EQ(m.fp, 1);
  EXPECT_EQ(m.id_switches, 1);
  EXPECT_EQ(m.fragmentations, 1);         // object 1 tracked in two pieces
  EXPECT_NEAR(m.mota, (9.0 - 1 - 1) / 10.0, 1e-12);
  EXPECT_NEAR(m.motp, 1.0, 1e-12);
  EXPECT_EQ(m.mostly_tracked, 1);         // object 2: 5/5
  EXPECT_EQ(m.partially_tracked, 1);      // object 1: 4/5 = 0.8 is not > 0.8
  EXPECT_EQ(m.mostly_lost, 0);
}

TEST(Identity, Idf1UsesTheBestOneToOneIdMapping) {
  Case c;
  const ClearMot m = evaluate(c.sequence, c.predictions).tracking[0];
  // Mapping 1->3 (4 frames) and 2->4 (3 frames): IDTP 7 of 10 truths and 10 predictions.
  EXPECT_EQ(m.idtp, 7);
  EXPECT_EQ(m.idfn, 3);
  EXPECT_EQ(m.idfp, 3);
  EXPECT_NEAR(m.idf1, 14.0 / 20.0, 1e-12);
}

TEST(Hota, DetectionAndAssociationAccuracyAtOneThreshold) {
  Case c;
  const ClearMot m = evaluate(c.sequence, c.predictions).tracking[0];
  // TP 9, FN 1, FP 1 -> DetA = 9/11.
  EXPECT_NEAR(m.deta, 9.0 / 11.0, 1e-12);
  // Pairs (1,3) 4 matches, (2,4) 3, (2,5) 2; A = TPA / (|gt| + |track| - TPA):
  // 4/(5+4-4) = 0.8, 3/(5+3-3) = 0.6, 2/(5+2-2) = 0.4 -> AssA = (4*0.8 + 3*0.6 + 2*0.4) / 9.
  EXPECT_NEAR(m.assa, 5.8 / 9.0, 1e-12);
  EXPECT_NEAR(m.hota, std::sqrt(9.0 / 11.0 * 5.8 / 9.0), 1e-12);
  EXPECT_NEAR(m.loca, 1.0, 1e-12);
}

TEST(ClearMot, PerfectTrackingScoresOne) {
  Sequence s = testing::empty_sequence(3);
  Predictions p;
  for (int64_t f = 1; f <= 3; ++f) {
    s.objects[f] = {object(1, 10, 10, 4, 10), object(2, 40, 10, 4, 10)};
    p.boxes[f] = {oriented(11, 10, 10, 4, 10), oriented(12, 40, 10, 4, 10)};
  }
  const EvaluationResult r = evaluate(s, p);
  for (const ClearMot& m : r.tracking) {
    EXPECT_DOUBLE_EQ(m.mota, 1.0);
    EXPECT_DOUBLE_EQ(m.idf1, 1.0);
    EXPECT_DOUBLE_EQ(m.hota, 1.0);
    EXPECT_EQ(m.id_switches, 0);
  }
  ASSERT_TRUE(r.hota_averaged.has_value());
  EXPECT_DOUBLE_EQ(r.hota_averaged->hota, 1.0);
}

TEST(ClearMot, LowerIouThresholdAcceptsLooserBoxes) {
  // A box shifted by 4 px along a 10 x 4 car: IoU = 6*4 / (2*40 - 24) = 24/56 = 0.4286.
  Sequence s = testing::empty_sequence(1);
  s.objects[1] = {object(1, 10, 10, 4, 10)};
  Predictions p;
  p.boxes[1] = {oriented(1, 14, 10, 4, 10)};
  const EvaluationResult r = evaluate(s, p);
  EXPECT_EQ(r.tracking[0].tp, 0);  // at 0.5: a miss and a false positive
  EXPECT_EQ(r.tracking[0].fp, 1);
  EXPECT_EQ(r.tracking[0].fn, 1);
  EXPECT_EQ(r.tracking[1].tp, 1);  // at 0.3: a hit
  EXPECT_NEAR(r.tracking[1].motp, 24.0 / 56.0, 1e-12);
  // HOTA averaged over alphas: matched for alpha <= 0.4286 (alphas 0.05..0.40: 8 of 19), DetA 1 there, 0 elsewhere.
  EXPECT_NEAR(r.hota_averaged->deta, (8 * 1.0 + 11 * (0.0)) / 19.0, 1e-12);
}

TEST(ClearMot, PredictionsOnStoppedVehiclesAreRemovedButOnParkedOnesAreFalsePositives) {
  Sequence s = testing::empty_sequence(1);
  s.objects[1] = {object(1, 10, 10, 4, 10, 0, false, false), object(2, 40, 10, 4, 10, 0, false, true)};
  Predictions p;
  p.boxes[1] = {oriented(1, 10, 10, 4, 10), oriented(2, 40, 10, 4, 10)};
  const ClearMot m = evaluate(s, p).tracking[0];
  EXPECT_EQ(m.gt_detections, 0);
  EXPECT_EQ(m.fp, 1);  // the parked car
  EXPECT_EQ(m.tracker_detections, 1);
}

TEST(ClearMot, SkippedWithoutTrackIds) {
  Sequence s = testing::empty_sequence(1);
  s.objects[1] = {object(1, 10, 10, 4, 10)};
  Predictions p;
  p.add_boxes(1, {OrientedBox{10, 10, 4, 10, 0}});
  const EvaluationResult r = evaluate(s, p);
  EXPECT_FALSE(r.has_identities);
  EXPECT_TRUE(r.tracking.empty());
  EXPECT_EQ(r.completeness.correct, 1);
}

}  // namespace
}  // namespace uavmot::eval
