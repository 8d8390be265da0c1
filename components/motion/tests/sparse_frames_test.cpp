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

struct Summary {
  size_t fewest_features = SIZE_MAX;
  double worst_error = 0.0;
  int valid = 0;
};

Summary summarise(const testing::WarpedSequence& sequence, const std::vector<MotionEstimate>& estimates) {
  Summary s;
  const cv::Size size = sequence.options().frame_size;
  for (size_t i = 1; i < estimates.size(); ++i) {
    const auto& e = estimates[i];
    s.fewest_features = std::min(s.fewest_features, e.features.size());
    if (!e.quality.valid) continue;
    ++s.valid;
    s.worst_error = std::max(s.worst_error, mean_transfer_error(e.homography, sequence.true_homography(static_cast<int>(e.frame_index)),
                                                                size.width, size.height));
  }
  return s;
}

TEST(SparseFrames, WeakCornersServeWhenTooFewAreStrong) {
  const testing::WarpedSequence sequence(test::camera(8.0, 0.1));
  const int frames = 12;
  MotionOptions off;
  off.sparse_response_factor = 1.0;
  const Summary without = summarise(sequence, run_faded(sequence, frames, 0.25, off));
  const Summary with = summarise(sequence, run_faded(sequence, frames, 0.25, MotionOptions{}));
  std::printf("faded frames: without the sparse pass %zu features at least, %d valid, worst %.3f px; with it %zu, %d, %.3f px\n",
              without.fewest_features, without.valid, without.worst_error, with.fewest_features, with.valid, with.worst_error);
  const double sparse = MotionOptions{}.sparse_features_fraction * MotionOptions{}.max_features;
  EXPECT_LT(static_cast<double>(without.fewest_features), sparse) << "the faded texture must be sparse at the full response";
  EXPECT_LT(without.valid, frames - 1) << "too few strong corners to hold a homography";
  EXPECT_GT(with.fewest_features, without.fewest_features);
  EXPECT_EQ(with.valid, frames - 1);
  EXPECT_LE(with.worst_error, 0.3);
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
