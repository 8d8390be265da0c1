// Frame-to-frame homographies against the exact ground truth of warped CLIF texture.
#include <cstdio>

#include <gtest/gtest.h>

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
