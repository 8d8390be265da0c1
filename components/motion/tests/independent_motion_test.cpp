// Moving/stationary classification against ground truth: textured patches moving 0.3-2 px/frame
// over warped CLIF ground (vehicles) and patches standing still (parked vehicles).
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "test_support.hpp"

namespace uavmot::motion {
namespace {

struct Counts {
  int on_moving = 0, on_moving_classified = 0;    // recall
  int classified_moving = 0, correct_moving = 0;  // precision
  int on_parked = 0, parked_moving = 0;
  int on_background = 0, background_moving = 0;
  int ambiguous = 0;
  double velocity_error_sum = 0;
  int velocity_error_n = 0;
};

// Features within 2 px inside or half an LK window outside a patch border are ambiguous: their
// tracking window sees the patch edge, so they legitimately move with it (or not).
Counts classify(const testing::WarpedSequence& sequence, const std::vector<MotionEstimate>& estimates, int warm_up,
                int min_age) {
  Counts c;
  const double outer_margin = resolved_for_scene(MotionOptions{}, SceneInfo{}).lk_window_px / 2 + 1.0;  // test::run's scene
  for (const auto& e : estimates) {
    const int k = static_cast<int>(e.frame_index);
    if (k <= warm_up) continue;
    for (const auto& f : e.features) {
      const int patch = sequence.patch_at(k, f.position, 2.0, outer_margin);
      if (patch == -2) {
        ++c.ambiguous;
        continue;
      }
      const bool truly_moving =
          patch >= 0 && cv::norm(sequence.options().patches[static_cast<size_t>(patch)].velocity) > 0.0;
      if (f.moving) {
        ++c.classified_moving;
        if (truly_moving) ++c.correct_moving;
      }
      if (truly_moving) {
        if (static_cast<int>(f.age) < min_age) continue;
        ++c.on_moving;
        if (f.moving) {
          ++c.on_moving_classified;
          c.velocity_error_sum += cv::norm(f.velocity - sequence.relative_velocity(patch, k, f.position));
          ++c.velocity_error_n;
        }
      } else if (patch >= 0) {
        ++c.on_parked;
        c.parked_moving += f.moving ? 1 : 0;
      } else {
        ++c.on_background;
        c.background_moving += f.moving ? 1 : 0;
      }
    }
  }
  return c;
}

void check_sequence(const char* name, testing::WarpedSequence& sequence, int frames, double min_speed,
                    double max_speed) {
  sequence.set_patches(testing::scatter_patches(sequence, frames / 2, 40, 20, min_speed, max_speed, 11));
  const auto estimates = test::run(sequence, frames);
  const MotionOptions defaults;
  const Counts c = classify(sequence, estimates, 10, defaults.min_track_frames + defaults.confirm_frames);
  const double precision = c.classified_moving ? static_cast<double>(c.correct_moving) / c.classified_moving : 0.0;
  const double recall = c.on_moving ? static_cast<double>(c.on_moving_classified) / c.on_moving : 0.0;
  const double parked_rate = c.on_parked ? static_cast<double>(c.parked_moving) / c.on_parked : 0.0;
  const double background_rate = c.on_background ? static_cast<double>(c.background_moving) / c.on_background : 0.0;
  const double velocity_error = c.velocity_error_n ? c.velocity_error_sum / c.velocity_error_n : 0.0;
  std::printf(
      "%s: precision %.3f (%d/%d), recall %.3f (%d/%d), parked moving %d/%d, background moving %d/%d, "
      "mean velocity error %.3f px/frame, %d ambiguous (patch border) feature-frames excluded\n",
      name, precision, c.correct_moving, c.classified_moving, recall, c.on_moving_classified, c.on_moving,
      c.parked_moving, c.on_parked, c.background_moving, c.on_background, velocity_error, c.ambiguous);
  EXPECT_GE(c.on_moving, 200) << "too few features on moving patches to measure";
  EXPECT_GE(c.on_parked, 100) << "too few features on parked patches to measure";
  EXPECT_GE(precision, 0.95);
  EXPECT_GE(recall, 0.90);
  EXPECT_LE(parked_rate, 0.01);
  // Dense features (min 5 px apart) also sit on the ground just outside a patch, where the LK
  // window straddles the patch border and is dragged along with it: about 0.3 % of background
  // feature-frames here, all beside moving patches. Isolated noise alone stays far below this.
  EXPECT_LE(background_rate, 0.004);
  EXPECT_LE(velocity_error, 0.1);
}

TEST(IndependentMotion, SlowCameraMovingPatchesFoundParkedOnesNot) {
  testing::WarpedSequence sequence(test::camera(3.0, 0.05));
  check_sequence("slow camera, 0.3-2 px/frame", sequence, 50, 0.3, 2.0);
}

TEST(IndependentMotion, SubPixelMotionFromFastCamera) {
  auto options = test::camera(15.0, 0.2);
  options.jitter_px = 2.0;
  testing::WarpedSequence sequence(options);
  check_sequence("fast camera, 0.3-0.8 px/frame", sequence, 50, 0.3, 0.8);
}

// Features on moving patches decided moving at their first velocity (age 2: detected, then one
// frame tracked), i.e. by a strong start (MotionOptions::strong_motion_factor).
int moving_at_first_decision(double camera_speed_px, const MotionOptions& options) {
  testing::WarpedSequence sequence(test::camera(camera_speed_px, 0.05));
  sequence.set_patches(testing::scatter_patches(sequence, 15, 40, 0, 2.0, 3.0, 11));
  const auto estimates = test::run(sequence, 30, options);
  int count = 0;
  for (const auto& e : estimates) {
    for (const auto& f : e.features) {
      const int patch = sequence.patch_at(static_cast<int>(e.frame_index), f.position, 2.0, 8.0);
      count += patch >= 0 && f.age == 2 && f.moving ? 1 : 0;
    }
  }
  return count;
}

TEST(IndependentMotion, OneFrameDecidesOnlyUnderACameraThatCarriesCarsOutOfViewQuickly) {
  const MotionOptions defaults;
  ASSERT_GT(defaults.strong_motion_factor, 0.0);
  // 15 px/frame over 540 rows: the ground crosses the image in 36 frames, under the 60 that count.
  const int fast = moving_at_first_decision(15.0, defaults);
  // 3 px/frame: 180 frames; a frame of latency costs little, and one velocity does not decide.
  const int slow = moving_at_first_decision(3.0, defaults);
  MotionOptions always = defaults;
  always.strong_motion_max_view_frames = 0.0;
  const int slow_always = moving_at_first_decision(3.0, always);
  std::printf("moving at the first decision: fast camera %d, slow camera %d, slow camera without the gate %d\n", fast,
              slow, slow_always);
  EXPECT_GE(fast, 10);
  EXPECT_EQ(slow, 0);
  EXPECT_GE(slow_always, 10);
}

TEST(IndependentMotion, VelocitySigmaIsPositiveOnceTracked) {
  const testing::WarpedSequence sequence(test::camera(3.0, 0.05));
  const auto estimates = test::run(sequence, 8);
  int checked = 0;
  for (const auto& f : estimates.back().features) {
    if (f.age < 2) {
      EXPECT_EQ(f.velocity_sigma, 0.0);
      continue;
    }
    EXPECT_GT(f.velocity_sigma, 0.0);
    EXPECT_LT(f.velocity_sigma, 0.2);
    ++checked;
  }
  EXPECT_GT(checked, 100);
}

}  // namespace
}  // namespace uavmot::motion
