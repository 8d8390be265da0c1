// The hand-written closing and hole filling give exactly what the OpenCV calls they replace give.

#include "../src/binary_mask.hpp"

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

namespace uavmot::segmentation {
namespace {

// Random blob-like masks: a few filled ellipses and rectangles with holes and speckle.
cv::Mat random_mask(cv::RNG& rng) {
  cv::Mat mask = cv::Mat::zeros(rng.uniform(1, 40), rng.uniform(1, 40), CV_8U);
  for (int i = rng.uniform(0, 4); i > 0; --i) {
    const cv::Point centre(rng.uniform(0, mask.cols), rng.uniform(0, mask.rows));
    cv::ellipse(mask, centre, cv::Size(rng.uniform(1, 12), rng.uniform(1, 8)), rng.uniform(0, 180), 0, 360,
                cv::Scalar(255), cv::FILLED);
    cv::rectangle(mask, cv::Rect(centre, cv::Size(rng.uniform(1, 4), rng.uniform(1, 4))), cv::Scalar(0), cv::FILLED);
  }
  for (int i = rng.uniform(0, 30); i > 0; --i) {
    mask.at<uchar>(rng.uniform(0, mask.rows), rng.uniform(0, mask.cols)) ^= 255;
  }
  return mask;
}

TEST(BinaryMask, ClosingEqualsOpenCvMorphologyEx) {
  cv::RNG rng(11);
  for (int trial = 0; trial < 2000; ++trial) {
    const cv::Mat mask = random_mask(rng);
    const int size = 2 * rng.uniform(0, 4) + 1;
    cv::Mat expected;
    cv::morphologyEx(mask, expected, cv::MORPH_CLOSE, cv::getStructuringElement(cv::MORPH_RECT, cv::Size(size, size)));
    cv::Mat actual = mask.clone();
    close_binary(actual, size);
    ASSERT_EQ(cv::countNonZero(actual != expected), 0) << "trial " << trial << ", size " << size << "\n" << mask;
  }
}

TEST(BinaryMask, HoleFillingEqualsFillingTheExternalContours) {
  cv::RNG rng(12);
  for (int trial = 0; trial < 2000; ++trial) {
    const cv::Mat mask = random_mask(rng);
    std::vector<std::vector<cv::Point>> contours;
    cv::findContours(mask.clone(), contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_NONE);
    cv::Mat expected = cv::Mat::zeros(mask.size(), CV_8U);
    cv::drawContours(expected, contours, -1, cv::Scalar(255), cv::FILLED);
    cv::Mat actual = mask.clone();
    fill_holes(actual);
    ASSERT_EQ(cv::countNonZero(actual != expected), 0) << "trial " << trial << "\n" << mask;
  }
}

TEST(BinaryMask, ARingIsFilledAndABorderTouchingNotchIsNot) {
  cv::Mat ring = cv::Mat::zeros(9, 9, CV_8U);
  cv::rectangle(ring, cv::Rect(1, 1, 7, 7), cv::Scalar(255), 1);
  fill_holes(ring);
  EXPECT_EQ(cv::countNonZero(ring), 49);
  cv::Mat notch = cv::Mat::zeros(5, 5, CV_8U);
  notch.colRange(1, 4).setTo(255);
  notch.at<uchar>(0, 2) = 0;  // open to the border: not a hole
  notch.at<uchar>(1, 2) = 0;
  fill_holes(notch);
  EXPECT_EQ(notch.at<uchar>(1, 2), 0);
}

}  // namespace
}  // namespace uavmot::segmentation
