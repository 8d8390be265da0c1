// Frames with too few corners above min_corner_response (blur, a field, water) are searched again
// at a lower response, so the homography still rests on the ground.
#include <algorithm>
#include <cstdint>
#include <cstdio>

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "test_support.hpp"

namespace uavmot::motion {
namespace {

// The warped CLIF texture at `contrast` of its grey range around mid-grey, blurred.
std::vector<MotionEstimate> run_faded(const testing::WarpedSequence& sequence, int frames, double contrast,
                                      const MotionOptions& options) {
  MotionEstimator estimator(options);
  std::vector<MotionEstimate> out;
  for (int k = 1; k <= frames; ++k) {
    cv::Mat faded;
    sequence.frame(k).convertTo(faded, CV_8U, contrast, 128.0 * (1.0 - contrast));
    cv::GaussianBlur(faded, faded, cv::Size(5, 5), 1.0);
    out.push_back(estimator.process(test::make_frame(faded, k)));
  }
  return out;
}

// The fewest features any estimate after the first carried.
size_t fewest_features(const std::vector<MotionEstimate>& estimates) {
  size_t fewest = SIZE_MAX;
  for (size_t i = 1; i < estimates.size(); ++i) fewest = std::min(fewest, estimates[i].features.size());
  return fewest;
}

TEST(SparseFrames, WeakCornersServeWhenTooFewAreStrong) {
  const testing::WarpedSequence sequence(test::camera(8.0, 0.1));
  const int frames = 12;
  MotionOptions off;
  off.sparse_response_factor = 1.0;
  const auto faded_without = run_faded(sequence, frames, 0.25, off);
  const auto faded_with = run_faded(sequence, frames, 0.25, MotionOptions{});
  const test::ErrorStats without = test::transfer_errors(sequence, faded_without);
  const test::ErrorStats with = test::transfer_errors(sequence, faded_with);
  const size_t fewest_without = fewest_features(faded_without), fewest_with = fewest_features(faded_with);
  std::printf("faded frames: without the sparse pass %zu features at least, %d valid, worst %.3f px; with it %zu, %d, %.3f px\n",
              fewest_without, without.valid, without.max, fewest_with, with.valid, with.max);
  const double sparse = MotionOptions{}.sparse_features_fraction * MotionOptions{}.max_features;
  EXPECT_LT(static_cast<double>(fewest_without), sparse) << "the faded texture must be sparse at the full response";
  EXPECT_LT(without.valid, frames - 1) << "too few strong corners to hold a homography";
  EXPECT_GT(fewest_with, fewest_without);
  EXPECT_EQ(with.valid, frames - 1);
  EXPECT_LE(with.max, 0.3);
}

TEST(SparseFrames, FramesRichInCornersAreUnchanged) {
  const testing::WarpedSequence sequence(test::camera(8.0, 0.1));
  MotionOptions off;
  off.sparse_response_factor = 1.0;
  const auto a = test::run(sequence, 6, off);
  const auto b = test::run(sequence, 6);
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].features.size(), b[i].features.size());
    EXPECT_EQ(a[i].homography, b[i].homography);
  }
}

}  // namespace
}  // namespace uavmot::motion
