// Scenario tests against the simulator's exact ground truth (label `scenario`): homography
// transfer error per preset, and moving-feature precision/recall with parked vehicles.
#include <cmath>
#include <cstdio>
#include <numeric>

#include <gtest/gtest.h>

#include "uavmot/motion/motion_estimator.hpp"
#include "uavmot/sim/simulator.hpp"

namespace uavmot::motion {
namespace {

struct ScenarioScore {
  MotionStats stats;                   // the estimator's own counts over the run
  std::vector<double> transfer_error;  // per valid frame pair
  int pairs = 0, valid = 0;
  int on_moving = 0, on_moving_classified = 0;  // objects moving >= 0.3 px/frame, features old enough
  int classified_moving = 0, correct_moving = 0;
  int on_parked = 0, parked_moving = 0;         // parked vehicles (never move)
  int on_background = 0, background_moving = 0;
  int ambiguous = 0;
  double velocity_error_sum = 0;
  int velocity_error_n = 0;

  double mean_error() const {
    return transfer_error.empty() ? 0.0
                                  : std::accumulate(transfer_error.begin(), transfer_error.end(), 0.0) /
                                        static_cast<double>(transfer_error.size());
  }
  double precision() const { return classified_moving ? double(correct_moving) / classified_moving : 0.0; }
  double recall() const { return on_moving ? double(on_moving_classified) / on_moving : 0.0; }
};

// Recall counts features on vehicles moving at least `recall_speed_px` px/frame.
bool window_sees_moving_vehicle(const sim::SimFrame& frame, const cv::Point2d& p, double band) {
  for (const auto& o : frame.objects) {
    if (!o.moving) continue;
    OrientedBox grown = o.box;
    grown.width += 2 * band;
    grown.length += 2 * band;
    if (box_contains(grown, p)) return true;
  }
  return false;
}

ScenarioScore run_preset(const std::string& preset, int frames, double recall_speed_px = 0.3, uint64_t seed = 42) {
  sim::Scenario scenario = sim::preset_scenario(preset);
  scenario.frames = frames;
  sim::Simulator simulator(scenario, seed);
  const MotionOptions options;
  MotionEstimator estimator(options, simulator.scene());
  const int warm_up = 10;
  const auto min_age = static_cast<uint32_t>(options.min_track_frames + options.confirm_frames);
  // A tracking window that straddles a vehicle border or its shadow (about 2.3 px beyond the
  // footprint in the presets) sees both the vehicle and the ground: features there are
  // ambiguous and left out of the counts.
  const double band = estimator.options().lk_window_px / 2 + 4.0;  // the window for this scene
  ScenarioScore s;
  sim::SimFrame frame;
  while (simulator.next(frame)) {
    Frame input;
    input.stream_id = preset;
    input.index = frame.index;
    input.image = frame.image;
    const MotionEstimate e = estimator.process(input);
    if (frame.index == 1) continue;
    ++s.pairs;
    if (e.quality.valid) {
      ++s.valid;
      s.transfer_error.push_back(mean_transfer_error(e.homography, frame.homography_from_previous, frame.image.cols,
                                                     frame.image.rows));
    }
    if (frame.index <= warm_up) continue;
    for (const auto& f : e.features) {
      const int exact = sim::object_at(frame, f.position, 0.0);
      const int near = sim::object_at(frame, f.position, band);
      if (exact == 0 && near != 0) {
        ++s.ambiguous;
        continue;
      }
      const sim::ObjectTruth* object = exact ? sim::find_object(frame, exact) : nullptr;
      // Inside a vehicle but within 1 px of its border is ambiguous as well.
      if (object && sim::object_at(frame, f.position + cv::Point2d(1.5, 0), 0.0) != exact) {
        ++s.ambiguous;
        continue;
      }
      const bool on_moving_object = object && object->moving;
      if (f.moving) {
        ++s.classified_moving;
        if (on_moving_object) ++s.correct_moving;
      }
      if (on_moving_object) {
        if (cv::norm(object->velocity_px) >= recall_speed_px && f.age >= min_age) {
          ++s.on_moving;
          if (f.moving) {
            ++s.on_moving_classified;
            s.velocity_error_sum += cv::norm(f.velocity - object->velocity_px);
            ++s.velocity_error_n;
          }
        }
      } else if (object && object->parked && window_sees_moving_vehicle(frame, f.position, band)) {
        // A parked car's feature whose window also covers a passing vehicle straddles a moving
        // border, as the ground features beside vehicles above: ambiguous.
        ++s.ambiguous;
      } else if (object && object->parked) {
        ++s.on_parked;
        s.parked_moving += f.moving ? 1 : 0;
      } else if (object) {
        // In traffic but below the moving threshold this frame (braking, queueing, crawling):
        // neither clearly moving nor parked, so it counts for neither side.
        ++s.ambiguous;
      } else {
        ++s.on_background;
        s.background_moving += f.moving ? 1 : 0;
      }
    }
  }
  s.stats = estimator.stats();
  std::printf(
      "%s: %d/%d valid, mean transfer error %.4f px; moving features precision %.3f (%d/%d) recall (>= %.1f "
      "px/frame) %.3f (%d/%d), mean velocity error %.3f px/frame; parked %d/%d moving; background %d/%d "
      "moving; %d ambiguous\n",
      preset.c_str(), s.valid, s.pairs, s.mean_error(), s.precision(), s.correct_moving, s.classified_moving,
      recall_speed_px, s.recall(), s.on_moving_classified, s.on_moving,
      s.velocity_error_n ? s.velocity_error_sum / s.velocity_error_n : 0.0, s.parked_moving, s.on_parked,
      s.background_moving, s.on_background, s.ambiguous);
  return s;
}

void expect_classification(const ScenarioScore& s) {
  EXPECT_GE(s.on_moving, 100) << "too few features on moving vehicles to measure";
  // Not 1.0: with dense features some ground corners right beside a vehicle (outside the
  // ambiguity band) are dragged along by the vehicle's edge inside their LK window.
  EXPECT_GE(s.precision(), 0.93);
  EXPECT_GE(s.recall(), 0.90);
  // Parked vehicles: no moving features beyond noise.
  EXPECT_LE(s.parked_moving, std::max(1, s.on_parked / 100));
}

TEST(SimScenario, Paper) {
  const ScenarioScore s = run_preset("paper", 80);
  EXPECT_EQ(s.valid, s.pairs);
  EXPECT_LE(s.mean_error(), 0.1);
  expect_classification(s);
  // A flat world: the parallax steps find no structure and hold nothing.
  EXPECT_GE(s.stats.decided_frames, 70);
  EXPECT_EQ(s.stats.structure_frames, 0);
  EXPECT_EQ(s.stats.structure_patch_holds, 0);
  EXPECT_EQ(describe_structure(s.stats).rfind("no 3-D structure found", 0), 0u) << describe_structure(s.stats);
}

TEST(SimScenario, TownWithBuildingsShowsStructureAndItsPixelsHoldFeatures) {
  // `urban3d`: roofs of 5-30 m under a camera at 300 m. The parallax fit finds the structure in most
  // frames and the structure-patch step holds silhouette corners and rooftop units still.
  const ScenarioScore s = run_preset("urban3d", 40);
  std::printf("urban3d: %s\n", describe_structure(s.stats).c_str());
  EXPECT_EQ(s.valid, s.pairs);
  EXPECT_GE(s.stats.structure_frames, s.stats.decided_frames / 2) << s.stats.decided_frames << " frames decided";
  EXPECT_GT(s.stats.structure_patch_holds, 0);
  EXPECT_EQ(describe_structure(s.stats).rfind("3-D structure (parallax) found in", 0), 0u) << describe_structure(s.stats);
}

TEST(SimScenario, Fastcam) {
  const ScenarioScore s = run_preset("fastcam", 80);
  EXPECT_EQ(s.valid, s.pairs);
  EXPECT_LE(s.mean_error(), 0.3);
  expect_classification(s);
}

TEST(SimScenario, SlowSubPixelMovers) {
  // In `slow` queues keep most vehicles at 0.2-0.3 px/frame: recall is asserted from 0.2 px/frame,
  // stricter than the 0.3 px/frame of the issue.
  const ScenarioScore s = run_preset("slow", 80, 0.2);
  EXPECT_EQ(s.valid, s.pairs);
  EXPECT_LE(s.mean_error(), 0.1);
  expect_classification(s);
}

}  // namespace
}  // namespace uavmot::motion
