// Frame-to-frame homographies against the exact ground truth of warped CLIF texture.
#include <cstdio>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "test_support.hpp"

namespace uavmot::motion {
namespace {

TEST(HomographyAccuracy, SlowCameraMeanTransferErrorBelowTenthPixel) {
  const testing::WarpedSequence sequence(test::camera(3.0, 0.05));
  const int frames = 40;
  const auto estimates = test::run(sequence, frames);
  EXPECT_FALSE(estimates[0].quality.valid) << "frame 1 has no previous frame";
  const test::ErrorStats s = test::transfer_errors(sequence, estimates);
  std::printf("slow camera: %d/%d valid, mean transfer error %.4f px, worst frame %.4f px\n", s.valid, frames - 1,
              s.mean, s.max);
  EXPECT_EQ(s.valid, frames - 1);
  EXPECT_LE(s.mean, 0.1);
  EXPECT_LE(s.max, 0.3);
}

TEST(HomographyAccuracy, FastCameraMeanTransferErrorBelowThirdPixel) {
  auto options = test::camera(20.0, 0.3);
  options.zoom_per_frame = 0.002;
  options.jitter_px = 3.0;
  const testing::WarpedSequence sequence(options);
  const int frames = 40;
  const auto estimates = test::run(sequence, frames);
  const test::ErrorStats s = test::transfer_errors(sequence, estimates);
  std::printf("fast camera: %d/%d valid, mean transfer error %.4f px, worst frame %.4f px\n", s.valid, frames - 1,
              s.mean, s.max);
  EXPECT_EQ(s.valid, frames - 1);
  EXPECT_LE(s.mean, 0.3);
}

// Frames 11-32 dropped: the camera moved 23 frames' worth (about 90 px) between two frames the estimator sees,
// far beyond what the quick attempt (lk_quick_levels) captures around the prediction. The frame is
// tracked again with the whole pyramid (the phase-correlation recovery is off here, so the retry
// alone is tested), and without that retry it is lost.
TEST(HomographyAccuracy, AJumpIsTrackedAgainWithTheWholePyramid) {
  const testing::WarpedSequence sequence(test::camera(4.0, 0.05));
  auto run_with = [&](const MotionOptions& o) {
    MotionEstimator estimator(o);
    std::vector<MotionEstimate> out;
    for (int k : {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 33, 34}) out.push_back(estimator.process(test::make_frame(sequence.frame(k), k)));
    return out;
  };
  MotionOptions o;
  o.recover_large_motion = false;
  ASSERT_LT(o.lk_quick_levels, o.pyramid_levels);
  const auto retried = run_with(o);
  const Homography truth = sequence.ground_to_frame(33) * sequence.ground_to_frame(10).inv();
  const cv::Size size = sequence.options().frame_size;
  ASSERT_TRUE(retried[10].quality.valid) << "the frame after the jump";
  const double error = mean_transfer_error(retried[10].homography, truth, size.width, size.height);
  std::printf("jump of 23 frames: mean transfer error %.4f px with the retry\n", error);
  EXPECT_LT(error, 0.3);
  EXPECT_TRUE(retried[11].quality.valid);

  MotionOptions quick_only = o;
  quick_only.pyramid_levels = o.lk_quick_levels;
  EXPECT_FALSE(run_with(quick_only)[10].quality.valid) << "the quick attempt alone should not capture the jump";
}

TEST(HomographyAccuracy, QualityReportsInliersAndResidual) {
  const testing::WarpedSequence sequence(test::camera(3.0, 0.05));
  const auto estimates = test::run(sequence, 5);
  for (size_t i = 1; i < estimates.size(); ++i) {
    const auto& q = estimates[i].quality;
    EXPECT_TRUE(q.valid);
    EXPECT_GE(q.inliers, 100u);
    EXPECT_GT(q.residual_px, 0.0);
    EXPECT_LT(q.residual_px, 0.5);
    EXPECT_DOUBLE_EQ(estimates[i].homography(2, 2), 1.0);
  }
}

}  // namespace
}  // namespace uavmot::motion
