// Features seeded on change (change_mask.hpp, detect_changed_corners): a small vehicle crossing a
// grid cell that already holds a ground feature gets no corner from the coverage grid, so it was
// never tracked (`small` and the far rows of `oblique` lost most of their misses this way). The
// frame difference after the homography finds it; the static ground, its noise and the sensor's
// gain drift do not light up.
#include <gtest/gtest.h>

#include <algorithm>

#include <opencv2/imgproc.hpp>

#include "change_mask.hpp"
#include "grid_corner_detector.hpp"

namespace uavmot::motion {
namespace {

// Textured ground seen from a camera that moved by (dx, dy) px, with an 8 x 3 px bright car at
// `car` (its top-left corner), sensor noise and a gain.
cv::Mat render(const cv::Mat& ground, double dx, double dy, cv::Point2d car, double gain, uint64_t noise_seed) {
  cv::Mat image;
  const cv::Matx23d shift(1, 0, -dx, 0, 1, -dy);
  cv::warpAffine(ground, image, shift, cv::Size(640, 480), cv::INTER_LINEAR, cv::BORDER_REFLECT);
  cv::rectangle(image, cv::Rect(cvRound(car.x), cvRound(car.y), 8, 3), cv::Scalar(230), cv::FILLED);
  cv::Mat noise(image.size(), CV_32F), out;
  cv::RNG rng(noise_seed);
  rng.fill(noise, cv::RNG::NORMAL, 0.0, 2.0);
  image.convertTo(out, CV_32F, gain);
  out += noise;
  out.convertTo(out, CV_8U);
  return out;
}

cv::Mat textured_ground() {
  cv::Mat ground(520, 700, CV_8UC1);
  cv::RNG rng(7);
  rng.fill(ground, cv::RNG::UNIFORM, 60, 200);
  cv::GaussianBlur(ground, ground, cv::Size(0, 0), 1.5);
  return ground;
}

TEST(ChangeSeeding, TheMovingCarChangesAndTheDriftingGroundDoesNot) {
  const cv::Mat ground = textured_ground();
  const cv::Mat previous = render(ground, 0.0, 0.0, {300, 200}, 1.0, 1);
  // The camera moved 3.4 px right and 1.2 px down, the car 1.5 px along the road, the gain 8 % up.
  const cv::Mat current = render(ground, 3.4, 1.2, {300 - 3.4 + 1.5, 200 - 1.2}, 1.08, 2);
  const Homography h(1, 0, -3.4, 0, 1, -1.2, 0, 0, 1);
  const MotionOptions o;
  const cv::Mat changed = changed_pixels(previous, current, h, o);
  ASSERT_EQ(changed.size(), current.size());
  const cv::Rect car(298, 197, 10, 5);  // the car now, and its previous place, give or take a pixel
  const int on_car = cv::countNonZero(changed(car));
  const int elsewhere = cv::countNonZero(changed) - on_car;
  EXPECT_GE(on_car, 6) << "the car's leading and trailing ends";
  EXPECT_LT(elsewhere, 0.001 * changed.total()) << "static ground under noise and gain drift";


  // The same car parked (a whole-pixel camera step, so it is drawn exactly where the ground took
  // it): nothing on it changes.
  const cv::Mat parked = render(ground, 3.0, 1.0, {297, 199}, 1.08, 2);
  const cv::Mat parked_changed = changed_pixels(previous, parked, Homography(1, 0, -3, 0, 1, -1, 0, 0, 1), o);
  EXPECT_LE(cv::countNonZero(parked_changed(cv::Rect(295, 197, 12, 7))), 1);
}

TEST(ChangeSeeding, ACarInACellThatHoldsAGroundFeatureStillGetsACorner) {
  cv::Mat gray(480, 640, CV_8UC1, cv::Scalar(100));  // flat asphalt: no corner but the car's
  cv::rectangle(gray, cv::Rect(300, 200, 8, 3), cv::Scalar(230), cv::FILLED);
  MotionOptions o;
  o.cell_size_px = 32;
  o.max_features = 1000;
  // Every cell already holds a ground feature; the car's cell too, 12 px from the car.
  std::vector<cv::Point2f> existing;
  for (int y = 16; y < 480; y += 32)
    for (int x = 16; x < 640; x += 32) existing.emplace_back(static_cast<float>(x), static_cast<float>(y));
  existing.emplace_back(290.0f, 192.0f);
  EXPECT_TRUE(detect_missing_corners(gray, existing, o).empty()) << "the coverage grid sees full cells";

  cv::Mat changed(gray.size(), CV_8UC1, cv::Scalar(0));
  changed(cv::Rect(299, 199, 10, 5)).setTo(255);
  const auto added = detect_changed_corners(gray, changed, existing, o, 10);
  ASSERT_FALSE(added.empty());
  EXPECT_LE(static_cast<int>(added.size()), o.change_features_per_cell);
  for (const auto& p : added) {
    EXPECT_TRUE(cv::Rect(298, 198, 12, 7).contains(cv::Point(cvRound(p.x), cvRound(p.y)))) << p;
    for (const auto& q : existing) EXPECT_GE(cv::norm(p - q), o.min_distance_px);
  }
  EXPECT_TRUE(detect_changed_corners(gray, changed, existing, o, 0).empty()) << "no budget, no corner";
  EXPECT_TRUE(detect_changed_corners(gray, cv::Mat(gray.size(), CV_8UC1, cv::Scalar(0)), existing, o, 10).empty());
}

// A roof edge under parallax changes along its whole length, a thin line tens of pixels long; a car
// changes at its two ends, within its length and its step. The long blob is no vehicle and seeds
// nothing; the car's blob is compact.
TEST(ChangeSeeding, ALongThinEdgeIsNoVehicleAndACarIs) {
  cv::Mat ground(480, 640, CV_8UC1, cv::Scalar(100));
  cv::rectangle(ground, cv::Rect(100, 100, 200, 120), cv::Scalar(170), cv::FILLED);  // a roof
  const cv::Mat previous = ground.clone();
  cv::Mat current(ground.size(), CV_8UC1, cv::Scalar(100));
  cv::rectangle(current, cv::Rect(102, 100, 200, 120), cv::Scalar(170), cv::FILLED);  // its parallax: 2 px
  cv::rectangle(previous, cv::Rect(400, 300, 14, 6), cv::Scalar(230), cv::FILLED);      // a car, 2 px on
  cv::rectangle(current, cv::Rect(402, 300, 14, 6), cv::Scalar(230), cv::FILLED);
  const cv::Mat changed = changed_pixels(previous, current, Homography::eye(), MotionOptions{});
  ASSERT_EQ(cv::countNonZero(changed(cv::Rect(100, 100, 2, 120))), 240) << "the roof's left edge changed";
  ASSERT_EQ(cv::countNonZero(changed(cv::Rect(400, 300, 2, 6))), 12) << "the car's back";
  ChangeBlobs blobs(changed, 40.0);  // 3 lengths of a 13 px car
  EXPECT_FALSE(blobs.compact_at(100, 150)) << "the roof's edge";
  EXPECT_FALSE(blobs.compact_at(100, 100)) << "asked again: the same blob, known";
  EXPECT_TRUE(blobs.compact_at(400, 302)) << "the car's back";
  EXPECT_TRUE(blobs.compact_at(414, 302)) << "the car's front";
  EXPECT_FALSE(blobs.compact_at(350, 350)) << "an unchanged pixel";
  EXPECT_FALSE(blobs.compact_at(-1, 5)) << "outside the image";
  ChangeBlobs off(changed, 0.0);
  EXPECT_TRUE(off.compact_at(100, 150)) << "no limit: every blob is compact";

  // Seeding: the roof's changed corners are seeded without the blob rule, only the car's with it.
  const auto near_car = [](const cv::Point2f& p) { return cv::Rect(396, 296, 24, 14).contains(cv::Point(cvRound(p.x), cvRound(p.y))); };
  const auto all = detect_changed_corners(current, changed, {}, MotionOptions{}, 100);
  EXPECT_TRUE(std::any_of(all.begin(), all.end(), [&](const cv::Point2f& p) { return !near_car(p); })) << "roof corners";
  ChangeBlobs fresh(changed, 40.0);
  const auto compact = detect_changed_corners(current, changed, {}, MotionOptions{}, 100, &fresh);
  ASSERT_FALSE(compact.empty());
  for (const auto& p : compact) EXPECT_TRUE(near_car(p)) << p;

  // A half-size mask (each pixel covering 2 x 2) seeds exactly what the same mask brought back to
  // full size does (the chain takes the difference on the half-size level at 1080p).
  cv::Mat coarse;
  cv::resize(changed, coarse, cv::Size(320, 240), 0.0, 0.0, cv::INTER_AREA);
  cv::threshold(coarse, coarse, 0, 255, cv::THRESH_BINARY);
  cv::Mat upsampled;
  cv::resize(coarse, upsampled, changed.size(), 0.0, 0.0, cv::INTER_NEAREST);
  ChangeBlobs full_blobs(upsampled, 40.0), half_blobs(coarse, 40.0, 2);
  const auto from_full = detect_changed_corners(current, upsampled, {}, MotionOptions{}, 100, &full_blobs);
  const auto from_half = detect_changed_corners(current, coarse, {}, MotionOptions{}, 100, &half_blobs, 2);
  ASSERT_FALSE(from_full.empty());
  EXPECT_EQ(from_half, from_full);
  EXPECT_TRUE(detect_changed_corners(current, coarse, {}, MotionOptions{}, 100, nullptr, 1).empty()) << "a mask of the wrong size";

  // The rule on its own: a bounding box as long as the limit is compact, one pixel more is not,
  // diagonals included (8-connected), and a query from anywhere on a long blob says so.
  cv::Mat mask(60, 60, CV_8UC1, cv::Scalar(0));
  for (int i = 0; i < 20; ++i) mask.at<uchar>(2 + i, 2 + i) = 255;  // a diagonal, 20 x 20
  mask(cv::Rect(30, 30, 19, 3)).setTo(255);                        // 19 px wide
  ChangeBlobs limit19(mask, 19.0);
  EXPECT_FALSE(limit19.compact_at(21, 21));
  EXPECT_FALSE(limit19.compact_at(2, 2));
  EXPECT_TRUE(limit19.compact_at(40, 31));
  ChangeBlobs limit20(mask, 20.0);
  EXPECT_TRUE(limit20.compact_at(10, 10));
}

}  // namespace
}  // namespace uavmot::motion
