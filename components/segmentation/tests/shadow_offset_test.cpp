// The shadow offset learnt from the regions: bright bodies on a road with their shadows cast one way.

#include "uavmot/segmentation/shadow_offset.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <vector>

#include <opencv2/imgproc.hpp>

namespace uavmot::segmentation {
namespace {

constexpr double kRoad = 100.0;

// A filled oriented rectangle of grey `value`, anti-aliased by 4 x 4 supersampling.
void paint(cv::Mat& image, const OrientedBox& box, double value) {
  const double a = box.angle_deg * CV_PI / 180.0, ca = std::cos(a), sa = std::sin(a);
  const cv::Rect2d bounds = axis_aligned_bounds(box);
  for (int y = std::max(0, static_cast<int>(bounds.y) - 1); y <= std::min(image.rows - 1, static_cast<int>(bounds.br().y) + 1); ++y) {
    for (int x = std::max(0, static_cast<int>(bounds.x) - 1); x <= std::min(image.cols - 1, static_cast<int>(bounds.br().x) + 1); ++x) {
      int hits = 0;
      for (int j = 0; j < 4; ++j) {
        for (int i = 0; i < 4; ++i) {
          const double dx = x - 0.375 + 0.25 * i - box.cx, dy = y - 0.375 + 0.25 * j - box.cy;
          hits += std::abs(dx * ca + dy * sa) <= box.length / 2 && std::abs(-dx * sa + dy * ca) <= box.width / 2;
        }
      }
      float& p = image.at<float>(y, x);
      p = static_cast<float>(p + (value - p) * hits / 16.0);
    }
  }
}

// The box of a body united with its shadow `s`: the body's box grown by |s| along each axis and
// moved by s / 2 (what a gradient blob of both gives).
OrientedBox with_shadow(const OrientedBox& body, cv::Vec2d s) {
  const double a = body.angle_deg * CV_PI / 180.0;
  const double along = s[0] * std::cos(a) + s[1] * std::sin(a), across = -s[0] * std::sin(a) + s[1] * std::cos(a);
  OrientedBox box = body;
  box.cx += s[0] / 2;
  box.cy += s[1] / 2;
  box.length += std::abs(along);
  box.width += std::abs(across);
  return box;
}

struct Scene {
  cv::Mat gray;
  std::vector<OrientedBox> boxes;  // what the segmentation would report: body and shadow
};

// Vehicles (5 x 12 px bodies of grey `body_grey`) in every direction over a road, each with its
// shadow at `shadow` (none when zero), darkening the road by 45 %.
Scene vehicles(cv::Vec2d shadow, double body_grey) {
  cv::Mat image(cv::Size(400, 400), CV_32F, cv::Scalar(kRoad));
  Scene scene;
  int k = 0;
  for (int row = 0; row < 6; ++row) {
    for (int col = 0; col < 6; ++col, ++k) {
      const OrientedBox body{40.0 + 60 * col + 0.3 * (k % 4), 40.0 + 60 * row + 0.2 * (k % 5), 5.0, 12.0, -90.0 + 17.0 * k};
      if (shadow != cv::Vec2d(0, 0)) {
        OrientedBox cast = body;
        cast.cx += shadow[0];
        cast.cy += shadow[1];
        paint(image, cast, 0.55 * kRoad);
      }
      paint(image, body, body_grey);
      scene.boxes.push_back(with_shadow(body, shadow));
    }
  }
  image.convertTo(scene.gray, CV_8U);
  return scene;
}

std::optional<cv::Vec2d> learnt(const Scene& scene, ShadowOffsetOptions options = {}) {
  options.max_offset_px = 5.0;
  options.min_regions = 30;
  ShadowOffset shadow(options);
  for (const auto& box : scene.boxes) shadow.observe(scene.gray, cv::Point(0, 0), box);
  return shadow.offset();
}

TEST(ShadowOffset, FindsTheShadowOfBrightBodiesWhateverWayTheyPoint) {
  for (const cv::Vec2d& s : {cv::Vec2d(2.0, 1.5), cv::Vec2d(-1.5, 2.5), cv::Vec2d(0.0, -3.0)}) {
    const auto found = learnt(vehicles(s, 190.0));
    ASSERT_TRUE(found.has_value()) << s;
    EXPECT_NEAR((*found)[0], s[0], 0.5) << s;
    EXPECT_NEAR((*found)[1], s[1], 0.5) << s;
  }
}

TEST(ShadowOffset, NoShadowNoOffset) {
  const auto found = learnt(vehicles(cv::Vec2d(0, 0), 190.0));
  // Nothing is darker than the road: no candidate scores above zero, or one within a step of none.
  if (found) {
    EXPECT_LE(std::hypot((*found)[0], (*found)[1]), 0.25 + 1e-9) << *found;
  }
}

TEST(ShadowOffset, ABrightHaloIsNoShadow) {
  // No shadow, but each bright body blurred onto the road on its sunny side and its box reaching
  // over plain road on the other: the band outside the sunny end is brighter than the road, so the
  // vote for the offset is positive, while the band that should be shadow is road.
  const cv::Vec2d s(2.0, 1.5);
  cv::Mat image(cv::Size(400, 400), CV_32F, cv::Scalar(kRoad));
  Scene scene;
  for (int k = 0; k < 36; ++k) {
    const OrientedBox body{40.0 + 60 * (k % 6), 40.0 + 60 * (k / 6), 5.0, 12.0, -90.0 + 17.0 * k};
    OrientedBox halo = body;
    halo.cx -= s[0];
    halo.cy -= s[1];
    paint(image, halo, 160.0);
    paint(image, body, 190.0);
    scene.boxes.push_back(with_shadow(body, s));
  }
  image.convertTo(scene.gray, CV_8U);
  EXPECT_FALSE(learnt(scene).has_value());
  ShadowOffsetOptions blind;
  blind.min_darkness = -1000.0;  // the darkness test off: the halo passes for a shadow
  EXPECT_TRUE(learnt(scene, blind).has_value());
}

TEST(ShadowOffset, RegionsThatDisagreeGiveNoOffset) {
  // Every second vehicle casts its shadow the other way (an oblique view, where one offset does not
  // hold for the whole image, looks like this to the estimator): the two halves of the votes differ.
  const Scene forward = vehicles(cv::Vec2d(2.0, 1.5), 190.0), backward = vehicles(cv::Vec2d(-2.0, -1.5), 190.0);
  ShadowOffset shadow(ShadowOffsetOptions{5.0, 0.25, 15.0, 10, 1.0, 0.0});
  for (size_t i = 0; i < forward.boxes.size(); ++i) {
    const Scene& scene = i % 2 == 0 ? forward : backward;
    shadow.observe(scene.gray, cv::Point(0, 0), scene.boxes[i]);
  }
  EXPECT_EQ(shadow.votes(), static_cast<int>(forward.boxes.size()));
  EXPECT_FALSE(shadow.offset().has_value());
}

TEST(ShadowOffset, DarkBodiesDoNotVote) {
  ShadowOffset shadow(ShadowOffsetOptions{5.0, 0.25, 15.0, 1});
  const Scene scene = vehicles(cv::Vec2d(2.0, 1.5), 60.0);
  for (const auto& box : scene.boxes) shadow.observe(scene.gray, cv::Point(0, 0), box);
  EXPECT_EQ(shadow.votes(), 0);
  EXPECT_FALSE(shadow.offset().has_value());
}

TEST(ShadowOffset, WaitsForEnoughRegionsAndForgetsThemOnReset) {
  const Scene scene = vehicles(cv::Vec2d(2.0, 1.5), 190.0);
  ShadowOffset shadow(ShadowOffsetOptions{5.0, 0.25, 15.0, 30});
  for (size_t i = 0; i < 20; ++i) shadow.observe(scene.gray, cv::Point(0, 0), scene.boxes[i]);
  EXPECT_FALSE(shadow.offset().has_value()) << "20 of the 30 regions needed";
  for (size_t i = 20; i < scene.boxes.size(); ++i) shadow.observe(scene.gray, cv::Point(0, 0), scene.boxes[i]);
  ASSERT_TRUE(shadow.offset().has_value());
  shadow.reset();  // the next frame
  EXPECT_EQ(shadow.votes(), 0);
  EXPECT_FALSE(shadow.offset().has_value());
}

TEST(ShadowOffset, ARegionCutOffByItsWindowDoesNotVote) {
  const Scene scene = vehicles(cv::Vec2d(2.0, 1.5), 190.0);
  ShadowOffset shadow(ShadowOffsetOptions{5.0, 0.25, 15.0, 1});
  const cv::Rect window(0, 0, 44, 44);  // holds only part of the first vehicle's box
  shadow.observe(scene.gray(window), window.tl(), scene.boxes[0]);
  EXPECT_EQ(shadow.votes(), 0);
  // A window holding the box (but not all of the bands beyond it) is enough.
  const cv::Rect wider(0, 0, 52, 52);
  shadow.observe(scene.gray(wider), wider.tl(), scene.boxes[0]);
  EXPECT_EQ(shadow.votes(), 1);
}

TEST(ShadowOffset, ABadBoxOrImageIsIgnored) {
  const Scene scene = vehicles(cv::Vec2d(2.0, 1.5), 190.0);
  ShadowOffset shadow(ShadowOffsetOptions{5.0, 0.25, 15.0, 1});
  OrientedBox nan_box = scene.boxes[0];
  nan_box.cx = std::nan("");
  shadow.observe(scene.gray, cv::Point(0, 0), nan_box);
  cv::Mat colour;
  cv::cvtColor(scene.gray, colour, cv::COLOR_GRAY2BGR);
  shadow.observe(colour, cv::Point(0, 0), scene.boxes[0]);
  shadow.observe(cv::Mat(), cv::Point(0, 0), scene.boxes[0]);
  EXPECT_EQ(shadow.votes(), 0);
  // An enormous search is bounded (coarser steps), not allocated in full.
  ShadowOffset huge(ShadowOffsetOptions{1e6, 0.25, 15.0, 1});
  EXPECT_FALSE(huge.offset().has_value());
}

TEST(ShadowOffset, TheBodyIsTheBlobShrunkByItsShadow) {
  // The inverse of with_shadow() for the size, whatever way the vehicle points and the sun shines.
  for (const double angle : {0.0, 30.0, 90.0, -60.0}) {
    for (const cv::Vec2d& s : {cv::Vec2d(2.0, 1.5), cv::Vec2d(-1.5, 2.5), cv::Vec2d(0.0, -3.0)}) {
      const OrientedBox body{100.0, 50.0, 5.0, 14.0, angle};
      const OrientedBox blob = with_shadow(body, s);
      const OrientedBox found = shrunk_by_shadow(blob, s);
      EXPECT_NEAR(found.length, body.length, 1e-9) << angle << " " << s;
      EXPECT_NEAR(found.width, body.width, 1e-9) << angle << " " << s;
      EXPECT_DOUBLE_EQ(found.cx, blob.cx);  // the centre is shadow_correction_factor's
      EXPECT_DOUBLE_EQ(found.angle_deg, blob.angle_deg);
    }
  }
  // An offset the box cannot hold leaves half of it.
  const OrientedBox small{10.0, 10.0, 2.0, 4.0, 0.0};
  const OrientedBox kept = shrunk_by_shadow(small, cv::Vec2d(6.0, 3.0));
  EXPECT_DOUBLE_EQ(kept.length, 2.0);
  EXPECT_DOUBLE_EQ(kept.width, 1.0);
  EXPECT_DOUBLE_EQ(shrunk_by_shadow(small, cv::Vec2d(0.0, 0.0)).length, 4.0);
}
}  // namespace
}  // namespace uavmot::segmentation
