// The structure-patch test (src/structure_patch.hpp) on rendered frames: textured ground under a
// camera translating 3.3 px/frame along x, a textured roof that moves with it plus its parallax of
// 0.4 px/frame along the same line (the epipolar direction of a level flight), and a textured car
// driving on the ground. The corner where the roof's edge crosses the ground is explained by
// static structure however its LK track slid; the car's corners are not, whether it drives across
// the line or along it faster than any structure, on a road of flat asphalt.

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "structure_patch.hpp"

namespace uavmot::motion {
namespace {

constexpr int kWidth = 240, kHeight = 160;
const cv::Point2f kCamera(3.3f, 0.0f);      // the ground's image motion per frame (sub-pixel, as in flight)
const cv::Point2f kEpipolar(1.0f, 0.0f);    // structure moves along this line, away from the epipole
constexpr float kRoofParallax = 0.4f;       // px/frame along kEpipolar (a roof of about 40 m at 300 m flight height)
constexpr double kCap = 0.6;                // the tallest structure's parallax here
const cv::Rect2f kRoofAt0(60, 40, 50, 40);  // frame 0
const cv::Rect2f kCarAt0(150, 90, 24, 10);

// Random grey values blurred by `blur_sigma` px: the smoother, the larger its features.
cv::Mat texture(int width, int height, uint64_t seed, double blur_sigma) {
  cv::Mat t(height, width, CV_8U);
  cv::RNG rng(seed);
  rng.fill(t, cv::RNG::UNIFORM, 40, 200);
  cv::GaussianBlur(t, t, cv::Size(0, 0), blur_sigma);
  return t;
}

// Draws `layer` (its pixel (0, 0) at `at`, sub-pixel) over `image`, anti-aliased at its border.
void draw_layer(cv::Mat& image, const cv::Mat& layer, cv::Point2f at) {
  const cv::Matx23d shift(1, 0, at.x, 0, 1, at.y);
  cv::Mat moved, coverage;
  cv::warpAffine(layer, moved, shift, image.size(), cv::INTER_LINEAR);
  cv::warpAffine(cv::Mat(layer.size(), CV_32F, cv::Scalar(1.0f)), coverage, shift, image.size(), cv::INTER_LINEAR);
  cv::Mat under, over;
  image.convertTo(under, CV_32F);
  moved.convertTo(over, CV_32F);
  cv::Mat blended = over.mul(coverage) + under.mul(1.0f - coverage);
  blended.convertTo(image, CV_8U);
}

// Frame `k`: the ground shifted by k x kCamera, the roof by k x (kCamera + parallax), the car by
// k x (kCamera + car_velocity), then sensor noise.
cv::Mat frame(int k, cv::Point2f car_velocity) {
  static const cv::Mat ground = texture(kWidth + 60, kHeight + 60, 1, 0.8);
  static const cv::Mat roof = texture(static_cast<int>(kRoofAt0.width), static_cast<int>(kRoofAt0.height), 2, 0.8);
  static const cv::Mat car = texture(static_cast<int>(kCarAt0.width), static_cast<int>(kCarAt0.height), 3, 1.5);
  cv::Mat image;
  const cv::Matx23d ground_shift(1, 0, k * kCamera.x - 30, 0, 1, k * kCamera.y - 30);
  cv::warpAffine(ground, image, ground_shift, cv::Size(kWidth, kHeight), cv::INTER_LINEAR);
  const float t = static_cast<float>(k);
  // The road: flat asphalt, a strip of the ground across the image.
  const cv::Rect2f road(0.0f, kCarAt0.y - 12.0f + t * kCamera.y, static_cast<float>(kWidth), kCarAt0.height + 24.0f);
  draw_layer(image, cv::Mat(cv::Size(kWidth + 60, static_cast<int>(road.height)), CV_8U, cv::Scalar(90)),
             cv::Point2f(t * kCamera.x - 30.0f, road.y));
  draw_layer(image, roof, kRoofAt0.tl() + t * (kCamera + kRoofParallax * kEpipolar));
  draw_layer(image, car, kCarAt0.tl() + t * (kCamera + car_velocity));
  cv::Mat noise(image.size(), CV_16S);
  cv::RNG rng(100 + static_cast<uint64_t>(k));
  rng.fill(noise, cv::RNG::NORMAL, 0, 2);
  cv::Mat noisy;
  image.convertTo(noisy, CV_16S);
  noisy += noise;
  noisy.convertTo(image, CV_8U);
  return image;
}

// The inverse of the frame's homography: current -> previous.
Homography camera_step_back() { return Homography(1, 0, -kCamera.x, 0, 1, -kCamera.y, 0, 0, 1); }

ParallaxFilter::StructureMotion structure_here() {
  ParallaxFilter::StructureMotion s;
  s.direction = cv::Vec2d(kEpipolar.x, kEpipolar.y);
  s.cap_px = kCap;
  s.both_ways = false;
  return s;
}

constexpr int kNow = 5;

PatchErrors errors_at(cv::Point2f to, cv::Point2f step, cv::Point2f car_velocity) {
  return structure_patch_errors(frame(kNow - 1, car_velocity), frame(kNow, car_velocity), to - step, to, camera_step_back(),
                                structure_here(), MotionOptions{}.structure_patch_radius_px);
}

cv::Point2f roof_corner_now() { return kRoofAt0.tl() + kNow * (kCamera + kRoofParallax * kEpipolar); }

TEST(StructurePatch, ARoofCornerOverGroundTextureIsExplainedHoweverItsTrackSlid) {
  const MotionOptions options;
  const cv::Point2f car_velocity(0.0f, 0.6f);
  // The corner's LK track slides along the ground's edge, off the epipolar line: the parallax step
  // alone takes it for a mover. Whichever way it slid, its pixels are ground and roof.
  for (const cv::Point2f slide : {cv::Point2f(0.0f, 0.5f), cv::Point2f(0.0f, -0.5f), cv::Point2f(0.9f, 0.3f)}) {
    const PatchErrors e = errors_at(roof_corner_now(), kCamera + slide, car_velocity);
    EXPECT_TRUE(structure_explains_patch(e, options)) << "slide " << slide << ": structure " << e.structure << ", own " << e.own;
  }
}

TEST(StructurePatch, ACarDrivingAcrossTheLineIsNotExplained) {
  const MotionOptions options;
  for (const float speed : {0.4f, 0.6f, -0.6f}) {
    const cv::Point2f car_velocity(0.0f, speed);
    const cv::Point2f on_car = kCarAt0.tl() + kNow * (kCamera + car_velocity) + cv::Point2f(6.0f, 5.0f);
    const PatchErrors e = errors_at(on_car, kCamera + car_velocity, car_velocity);
    EXPECT_FALSE(structure_explains_patch(e, options)) << "speed " << speed << ": structure " << e.structure << ", own " << e.own;
    EXPECT_GT(e.structure, 1.4 * e.own) << "speed " << speed;
  }
}

TEST(StructurePatch, ACarDrivingAlongTheLineFasterThanStructureIsNotExplained) {
  const MotionOptions options;
  const cv::Point2f car_velocity = 2.5f * static_cast<float>(kCap) * kEpipolar;
  const cv::Point2f on_car = kCarAt0.tl() + kNow * (kCamera + car_velocity) + cv::Point2f(6.0f, 5.0f);
  const PatchErrors e = errors_at(on_car, kCamera + car_velocity, car_velocity);
  EXPECT_FALSE(structure_explains_patch(e, options)) << "structure " << e.structure << ", own " << e.own;
}

TEST(StructurePatch, ARatioOfZeroTurnsTheTestOff) {
  MotionOptions options;
  options.structure_patch_ratio = 0.0;
  const PatchErrors e = errors_at(roof_corner_now(), kCamera + cv::Point2f(0.0f, 0.5f), cv::Point2f(0.0f, 0.6f));
  EXPECT_FALSE(structure_explains_patch(e, options));
  EXPECT_FALSE(structure_explains_patch(PatchErrors{0.0, 0.0}, options));
}

}  // namespace
}  // namespace uavmot::motion
