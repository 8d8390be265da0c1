// The 250 real CLIF 2007 frames (about 21 px/frame with some rotation, no ground truth): every
// frame pair gets a valid homography, and aligning frame k-1 onto frame k removes most of the
// photometric difference. Prints the median photometric residual for docs/motion.md.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <set>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "test_support.hpp"

namespace uavmot::motion {
namespace {

std::vector<std::string> clif_files() {
  std::vector<std::string> files;
  for (const auto& entry : std::filesystem::directory_iterator(test::clif_folder())) {
    if (entry.path().extension() == ".jpg") files.push_back(entry.path().string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

// Mean absolute grey-level difference between `current` and `previous` warped by `h`, over the
// pixels both frames see (20 px away from the warped border).
double photometric_residual(const cv::Mat& previous, const cv::Mat& current, const Homography& h) {
  cv::Mat warped, coverage;
  cv::warpPerspective(previous, warped, cv::Mat(cv::Matx33d(h)), current.size(), cv::INTER_LINEAR);
  cv::warpPerspective(cv::Mat(previous.size(), CV_8UC1, cv::Scalar(255)), coverage, cv::Mat(cv::Matx33d(h)),
                      current.size(), cv::INTER_NEAREST);
  cv::erode(coverage, coverage, cv::Mat(), cv::Point(-1, -1), 20);
  cv::Mat diff;
  cv::absdiff(warped, current, diff);
  return cv::mean(diff, coverage)[0];
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

TEST(ClifReal, EveryFramePairGetsAValidHomographyAndAlignsTheImages) {
  const auto files = clif_files();
  ASSERT_EQ(files.size(), 250u) << test::clif_folder();
  MotionEstimator estimator(MotionOptions{});
  std::vector<double> aligned, unaligned, inlier_ratio, residual_px;
  std::set<uint64_t> all_ids, moving_ids;
  cv::Mat previous;
  int valid = 0;
  for (size_t i = 0; i < files.size(); ++i) {
    const cv::Mat image = cv::imread(files[i], cv::IMREAD_GRAYSCALE);
    ASSERT_FALSE(image.empty()) << files[i];
    const auto e = estimator.process(test::make_frame(image, static_cast<int>(i) + 1));
    for (const auto& f : e.features) {
      all_ids.insert(f.id);
      if (f.moving) moving_ids.insert(f.id);
    }
    if (i > 0) {
      EXPECT_TRUE(e.quality.valid) << "frame " << i + 1;
      if (e.quality.valid) {
        ++valid;
        aligned.push_back(photometric_residual(previous, image, e.homography));
        unaligned.push_back(photometric_residual(previous, image, Homography::eye()));
        inlier_ratio.push_back(static_cast<double>(e.quality.inliers) / static_cast<double>(e.features.size()));
        residual_px.push_back(e.quality.residual_px);
        EXPECT_LT(aligned.back(), 0.5 * unaligned.back()) << "frame " << i + 1;
      }
    }
    previous = image;
  }
  ASSERT_FALSE(aligned.empty());
  std::printf(
      "CLIF 2007, 250 frames: %d/249 valid homographies; median photometric residual after alignment %.2f grey "
      "levels (%.2f unaligned), worst %.2f; median inlier RMS %.3f px; %zu feature tracks, %zu classified moving\n",
      valid, median(aligned), median(unaligned), *std::max_element(aligned.begin(), aligned.end()),
      median(residual_px), all_ids.size(), moving_ids.size());
  EXPECT_EQ(valid, 249);
  EXPECT_LT(median(residual_px), 0.5);
}

}  // namespace
}  // namespace uavmot::motion
