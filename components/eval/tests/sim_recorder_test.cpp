// Scoring in memory against the simulator, the way other components' accuracy tests do it.
#include <gtest/gtest.h>

#include "uavmot/eval/evaluate.hpp"
#include "uavmot/eval/sim_recorder.hpp"

namespace uavmot::eval {
namespace {

TEST(SimRecorder, TruthAsPredictionsScoresPerfectlyAndParkedBoxesAreFalseAlarms) {
  sim::Scenario s = sim::preset_scenario("dense");
  s.frames = 4;
  s.camera.width = 480;
  s.camera.height = 360;
  s.sensor.write_video = false;
  sim::Simulator simulator(s, 5);
  SimRecorder truth(simulator);
  Predictions predictions;
  sim::SimFrame frame;
  int64_t parked_boxes = 0;
  while (simulator.next(frame)) {
    truth.add(frame);
    TrackList tracks;
    tracks.frame_index = frame.index;
    for (const sim::ObjectTruth& o : frame.objects) {
      if (!o.moving && !o.parked) continue;
      Track t;
      t.id = static_cast<uint64_t>(o.id) + 100;
      t.state = TrackState::Confirmed;
      t.box = o.box;
      tracks.tracks.push_back(t);
      if (o.parked) ++parked_boxes;
    }
    predictions.add_tracks(tracks);
    // Features: one on every vehicle centre (moving flag from the truth), one on open ground.
    MotionEstimate motion;
    motion.frame_index = frame.index;
    motion.quality.valid = true;
    motion.homography = frame.homography_from_previous;
    for (const sim::ObjectTruth& o : frame.objects)
      if (o.visibility == 1.0) motion.features.push_back({static_cast<uint64_t>(o.id), {o.box.cx, o.box.cy}, o.velocity_px, 0.0, 1, o.moving});
    predictions.add_motion(motion);
  }
  ASSERT_GT(parked_boxes, 0);
  const EvaluationResult r = evaluate(truth.sequence(), predictions);
  EXPECT_EQ(r.sequence.length, 4);
  EXPECT_DOUBLE_EQ(r.sequence.gsd_m, 0.35);
  EXPECT_GT(r.completeness.instances, 20);
  EXPECT_EQ(r.completeness.correct, r.completeness.instances);
  EXPECT_EQ(r.false_alarms.on_parked, parked_boxes);
  EXPECT_EQ(r.false_alarms.false_alarms, parked_boxes);
  EXPECT_EQ(r.tracking[0].fn, 0);
  EXPECT_EQ(r.tracking[0].fp, parked_boxes);
  EXPECT_EQ(r.tracking[0].id_switches, 0);
  ASSERT_TRUE(r.homography.has_value());
  EXPECT_EQ(r.homography->frames, 3);
  EXPECT_NEAR(r.homography->max_px, 0.0, 1e-9);
  ASSERT_TRUE(r.features.has_value());
  EXPECT_EQ(r.features->frames_without_mask, 0);
  EXPECT_DOUBLE_EQ(r.features->precision(), 1.0);
  EXPECT_DOUBLE_EQ(r.features->recall(), 1.0);
  EXPECT_GT(r.features->true_negative, 0);  // the parked and waiting vehicles
}

}  // namespace
}  // namespace uavmot::eval
