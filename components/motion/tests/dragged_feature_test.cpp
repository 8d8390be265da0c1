// The dragged-feature check (src/dragged_feature.hpp) on a textured ground under a translating
// camera with a textured vehicle moving over it: a ground corner beside the vehicle that LK
// dragged along is recognised by its centre; the vehicle's own corners and a ground corner tracked
// with the ground are not.

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "dragged_feature.hpp"

namespace uavmot::motion {
namespace {

constexpr int kWidth = 200, kHeight = 120;
const cv::Point2f kCamera(2.0f, 1.0f);    // image motion of the ground per frame
const cv::Point2f kVehicle(3.0f, 0.0f);   // the vehicle's own motion over the ground per frame
const cv::Rect kVehicleAt0(80, 50, 24, 10);

cv::Mat texture(int width, int height, uint64_t seed) {
  cv::Mat t(height, width, CV_8U);
  cv::RNG rng(seed);
  rng.fill(t, cv::RNG::UNIFORM, 40, 200);
  cv::GaussianBlur(t, t, cv::Size(3, 3), 0.8);
  return t;
}

// Frame `k`: the ground shifted by k x kCamera, the vehicle by k x (kCamera + kVehicle).
cv::Mat frame(int k) {
  static const cv::Mat ground = texture(kWidth + 40, kHeight + 40, 1), car = texture(kVehicleAt0.width, kVehicleAt0.height, 2);
  cv::Mat image;
  const cv::Matx23d shift(1, 0, k * kCamera.x - 20, 0, 1, k * kCamera.y - 20);
  cv::warpAffine(ground, image, shift, cv::Size(kWidth, kHeight), cv::INTER_LINEAR);
  const cv::Point2f at = cv::Point2f(kVehicleAt0.tl()) + static_cast<float>(k) * (kCamera + kVehicle);
  car.copyTo(image(cv::Rect(cv::Point(cvRound(at.x), cvRound(at.y)), car.size())));
  return image;
}

// The inverse of the frame's homography: current -> previous.
Homography camera_step_back() { return Homography(1, 0, -kCamera.x, 0, 1, -kCamera.y, 0, 0, 1); }

TEST(DraggedFeature, AGroundCornerDraggedByTheVehicleBesideItIsRecognised) {
  const cv::Mat previous = frame(0), current = frame(1);
  const MotionOptions check;
  // 3 px below the vehicle's lower edge: ground, but an 11 px LK window there is half vehicle.
  const cv::Point2f from(92.0f, 62.0f);
  const cv::Point2f dragged = from + kCamera + kVehicle;
  EXPECT_TRUE(centre_follows_background(previous, current, from, dragged, camera_step_back(), check));
}

TEST(DraggedFeature, TheVehiclesOwnCornersAndTheGroundsAreKept) {
  const cv::Mat previous = frame(0), current = frame(1);
  const MotionOptions check;
  for (const cv::Point2f on_vehicle : {cv::Point2f(82.0f, 52.0f), cv::Point2f(100.0f, 57.0f), cv::Point2f(90.0f, 55.0f)}) {
    EXPECT_FALSE(centre_follows_background(previous, current, on_vehicle, on_vehicle + kCamera + kVehicle, camera_step_back(), check))
        << on_vehicle;
  }
  // A ground corner tracked with the ground: its own track is the ground's, nothing to decide.
  const cv::Point2f ground(40.0f, 30.0f);
  EXPECT_FALSE(centre_follows_background(previous, current, ground, ground + kCamera, camera_step_back(), check));
}

TEST(DraggedFeature, ARatioOfZeroTurnsTheCheckOff) {
  const cv::Point2f from(92.0f, 62.0f);
  MotionOptions off;
  off.dragged_ratio = 0.0;
  EXPECT_FALSE(centre_follows_background(frame(0), frame(1), from, from + kCamera + kVehicle, camera_step_back(), off));
}

// A lane marking beside a car: the car in the feature's LK window drags it along the marking, and
// its centre, a line along that motion, matches either way. The share of its gradient along the
// motion says so; a corner's and a blob's do not.
TEST(DraggedFeature, ACentreThatIsALineAlongItsMotionCannotShowIt) {
  cv::Mat road(40, 60, CV_8UC1, cv::Scalar(80));
  road.rowRange(19, 22).setTo(200);                       // a marking along x, 3 px wide
  cv::rectangle(road, cv::Rect(40, 5, 12, 8), cv::Scalar(30), cv::FILLED);  // a dark car: corners
  const MotionOptions o;
  const cv::Point2f on_marking(20.0f, 20.0f), car_corner(40.0f, 5.0f), flat(20.0f, 32.0f);
  const double aperture = 0.1;  // motion.aperture_ratio on real FMV (docs/motion.md)
  EXPECT_LT(centre_gradient_along(road, on_marking, {0.5, 0.0}, o), 0.01);
  EXPECT_LT(centre_gradient_along(road, on_marking, {0.5, 0.1}, o), aperture);
  EXPECT_GT(centre_gradient_along(road, on_marking, {0.0, 0.5}, o), 0.99);
  const double corner = centre_gradient_along(road, car_corner, {0.5, 0.0}, o);
  EXPECT_GT(corner, 0.3);
  EXPECT_LT(corner, 0.7);
  EXPECT_EQ(centre_gradient_along(road, flat, {0.5, 0.0}, o), 1.0);         // no gradient: nothing to say
  EXPECT_EQ(centre_gradient_along(road, on_marking, {0.0, 0.0}, o), 1.0);   // no motion
  EXPECT_EQ(centre_gradient_along(road, cv::Point2f(1.0f, 20.0f), {0.5, 0.0}, o), 1.0);  // at the edge
}

}  // namespace
}  // namespace uavmot::motion
