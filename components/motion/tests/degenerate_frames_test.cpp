// Bad frames never crash: degenerate content is flagged invalid with the identity, the frames
// after it recover, and malformed frames are InputErrors naming the frame.
#include <cstdio>
#include <functional>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "test_support.hpp"

namespace uavmot::motion {
namespace {

cv::Mat shifted(const cv::Mat& image, double dx, double dy) {
  cv::Mat out;
  cv::warpAffine(image, out, cv::Matx23d(1, 0, dx, 0, 1, dy), image.size(), cv::INTER_LINEAR, cv::BORDER_REFLECT_101);
  return out;
}

struct Case {
  const char* name;
  std::function<cv::Mat(const cv::Mat&)> spoil;
};

class DegenerateFrame : public ::testing::TestWithParam<int> {};

const std::vector<Case>& cases() {
  static const std::vector<Case> all = {
      {"black", [](const cv::Mat& m) { return cv::Mat(m.size(), CV_8UC1, cv::Scalar(0)); }},
      {"saturated", [](const cv::Mat& m) { return cv::Mat(m.size(), CV_8UC1, cv::Scalar(255)); }},
      {"random noise (scene cut)",
       [](const cv::Mat& m) {
         cv::Mat noise(m.size(), CV_8UC1);
         cv::RNG rng(3);
         rng.fill(noise, cv::RNG::UNIFORM, 0, 256);
         return noise;
       }},
      {"mirrored scene (scene cut)",
       [](const cv::Mat& m) {
         cv::Mat mirrored;
         cv::flip(m, mirrored, 0);
         return mirrored;
       }},
      {"huge shift (300 px)", [](const cv::Mat& m) { return shifted(m, 300, -120); }},
  };
  return all;
}

TEST_P(DegenerateFrame, FlaggedInvalidAndFollowingFramesRecover) {
  const Case& c = cases()[static_cast<size_t>(GetParam())];
  const testing::WarpedSequence sequence(test::camera(3.0, 0.05, {640, 480}));
  MotionEstimator estimator(MotionOptions{});
  const int bad = 6, frames = 14;
  std::vector<MotionEstimate> out;
  for (int k = 1; k <= frames; ++k) {
    cv::Mat image = sequence.frame(k);
    if (k == bad) image = c.spoil(image);
    ASSERT_NO_THROW(out.push_back(estimator.process(test::make_frame(image, k)))) << c.name;
  }
  const auto& spoilt = out[bad - 1];
  EXPECT_FALSE(spoilt.quality.valid) << c.name;
  EXPECT_EQ(spoilt.homography, Homography::eye()) << c.name;
  // The pair (bad, bad + 1) may also be unusable; from bad + 2 on every frame must be valid again
  // and accurate (a wrong "valid" homography would be worse than an invalid one).
  for (int k = bad + 2; k <= frames; ++k) {
    const auto& e = out[static_cast<size_t>(k - 1)];
    EXPECT_TRUE(e.quality.valid) << c.name << ": frame " << k;
    if (e.quality.valid) {
      EXPECT_LT(mean_transfer_error(e.homography, sequence.true_homography(k), 640, 480), 0.1) << c.name << " " << k;
    }
  }
  for (int k = 2; k < bad; ++k) EXPECT_TRUE(out[static_cast<size_t>(k - 1)].quality.valid);
  std::printf("%s: frame %d invalid, frame %d %s\n", c.name, bad, bad + 1,
              out[bad].quality.valid ? "valid" : "invalid");
}

INSTANTIATE_TEST_SUITE_P(Cases, DegenerateFrame, ::testing::Range(0, 5));

TEST(DegenerateInput, FeaturesRestartWithNewIdsAfterAnInvalidFrame) {
  const testing::WarpedSequence sequence(test::camera(3.0, 0.05, {640, 480}));
  MotionEstimator estimator(MotionOptions{});
  uint64_t max_id_before = 0;
  for (int k = 1; k <= 4; ++k) {
    for (const auto& f : estimator.process(test::make_frame(sequence.frame(k), k)).features) {
      max_id_before = std::max(max_id_before, f.id);
    }
  }
  const auto black = estimator.process(test::make_frame(cv::Mat(480, 640, CV_8UC1, cv::Scalar(0)), 5));
  EXPECT_TRUE(black.features.empty());
  const auto next = estimator.process(test::make_frame(sequence.frame(6), 6));
  EXPECT_FALSE(next.quality.valid);  // nothing to track from a black frame
  ASSERT_FALSE(next.features.empty());
  for (const auto& f : next.features) {
    EXPECT_GT(f.id, max_id_before);
    EXPECT_EQ(f.age, 1u);
    EXPECT_FALSE(f.moving);
  }
}

TEST(DegenerateInput, SizeChangeRestartsWithoutCrash) {
  const testing::WarpedSequence big(test::camera(3.0, 0.05, {640, 480}));
  const testing::WarpedSequence small(test::camera(3.0, 0.05, {320, 240}));
  MotionEstimator estimator(MotionOptions{});
  estimator.process(test::make_frame(big.frame(1), 1));
  estimator.process(test::make_frame(big.frame(2), 2));
  EXPECT_FALSE(estimator.process(test::make_frame(small.frame(3), 3)).quality.valid);
  EXPECT_TRUE(estimator.process(test::make_frame(small.frame(4), 4)).quality.valid);
}

TEST(DegenerateInput, MalformedFramesAreInputErrorsNamingTheFrame) {
  MotionEstimator estimator(MotionOptions{});
  Frame empty = test::make_frame(cv::Mat(), 12);
  try {
    estimator.process(empty);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("frame 12"), std::string::npos) << e.what();
  }
  EXPECT_THROW(estimator.process(test::make_frame(cv::Mat(100, 100, CV_16UC1, cv::Scalar(0)), 1)), InputError);
  EXPECT_THROW(estimator.process(test::make_frame(cv::Mat(100, 100, CV_8UC4, cv::Scalar(0)), 1)), InputError);
  EXPECT_THROW(estimator.process(test::make_frame(cv::Mat(10, 10, CV_8UC1, cv::Scalar(0)), 1)), InputError);
  // Still usable afterwards.
  const testing::WarpedSequence sequence(test::camera(3.0, 0.05, {320, 240}));
  estimator.process(test::make_frame(sequence.frame(1), 1));
  EXPECT_TRUE(estimator.process(test::make_frame(sequence.frame(2), 2)).quality.valid);
}

TEST(DegenerateInput, TooFewFeaturesIsInvalid) {
  // A flat image with a single bright square: at most a handful of corners.
  cv::Mat image(240, 320, CV_8UC1, cv::Scalar(90));
  image(cv::Rect(150, 100, 20, 20)).setTo(200);
  MotionEstimator estimator(MotionOptions{});
  estimator.process(test::make_frame(image, 1));
  const auto e = estimator.process(test::make_frame(shifted(image, 1.0, 0.5), 2));
  EXPECT_FALSE(e.quality.valid);
  EXPECT_EQ(e.homography, Homography::eye());
}

}  // namespace
}  // namespace uavmot::motion
