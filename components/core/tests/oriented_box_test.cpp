#include "uavmot/core/oriented_box.hpp"

#include <cmath>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

namespace uavmot {
namespace {

TEST(OrientedBox, NormalizesAxisAnglesIntoHalfOpenRange) {
  EXPECT_DOUBLE_EQ(normalize_axis_angle_deg(90.0), 90.0);
  EXPECT_DOUBLE_EQ(normalize_axis_angle_deg(-90.0), 90.0);
  EXPECT_DOUBLE_EQ(normalize_axis_angle_deg(135.0), -45.0);
  EXPECT_DOUBLE_EQ(normalize_axis_angle_deg(-135.0), 45.0);
  EXPECT_DOUBLE_EQ(normalize_axis_angle_deg(360.0 + 10.0), 10.0);
  EXPECT_DOUBLE_EQ(axis_angle_difference_deg(89.0, -89.0), -2.0);
}

TEST(OrientedBox, FromRotatedRectPutsLongerSideOnLength) {
  const auto tall = oriented_box_from_rotated_rect(cv::RotatedRect({10, 20}, {5, 15}, 0));
  EXPECT_DOUBLE_EQ(tall.length, 15);
  EXPECT_DOUBLE_EQ(tall.width, 5);
  EXPECT_DOUBLE_EQ(tall.angle_deg, 90);
  const auto wide = oriented_box_from_rotated_rect(cv::RotatedRect({10, 20}, {15, 5}, 30));
  EXPECT_DOUBLE_EQ(wide.length, 15);
  EXPECT_NEAR(wide.angle_deg, 30, 1e-6);
}

TEST(OrientedBox, AxisAlignedBoundsOfRotatedBox) {
  const OrientedBox box{100, 50, 2, 10, 90};
  const auto r = axis_aligned_bounds(box);
  EXPECT_NEAR(r.x, 99, 1e-9);
  EXPECT_NEAR(r.y, 45, 1e-9);
  EXPECT_NEAR(r.width, 2, 1e-9);
  EXPECT_NEAR(r.height, 10, 1e-9);
}

TEST(OrientedBox, PixelBoundsHoldEveryPixelTheBoundsReach) {
  // Bounds x in [98.6, 101.4], y in [44.7, 55.3]: pixels 98..102 and 44..56.
  const OrientedBox box{100, 50, 2.8, 10.6, 90};
  EXPECT_EQ(pixel_bounds(box), cv::Rect(98, 44, 5, 13));
  // Whole-pixel bounds keep one pixel to spare on the right and below.
  EXPECT_EQ(pixel_bounds(OrientedBox{10, 10, 4, 6, 0}), cv::Rect(7, 8, 7, 5));
}

TEST(OrientedBox, IntersectionAreaMatchesOpenCv) {
  const OrientedBox a{0, 0, 4, 10, 0};
  const OrientedBox b{3, 1, 4, 10, 30};
  std::vector<cv::Point2f> poly;
  cv::rotatedRectangleIntersection(to_rotated_rect(a), to_rotated_rect(b), poly);
  EXPECT_NEAR(intersection_area(a, b), cv::contourArea(poly), 1e-3);
  EXPECT_NEAR(intersection_area(a, a), 40.0, 1e-9);
  EXPECT_DOUBLE_EQ(intersection_area(a, OrientedBox{100, 0, 4, 10, 0}), 0.0);
  EXPECT_NEAR(intersection_over_union(a, a), 1.0, 1e-12);
}

TEST(OrientedBox, BoxCoordinatesRoundTripAndContainment) {
  const OrientedBox box{10, 20, 4, 12, 35};
  const cv::Point2d p(12.5, 22.0);
  const auto uv = to_box_coordinates(box, p);
  const auto back = from_box_coordinates(box, uv);
  EXPECT_NEAR(back.x, p.x, 1e-9);
  EXPECT_NEAR(back.y, p.y, 1e-9);
  EXPECT_TRUE(box_contains(box, {10, 20}));
  EXPECT_TRUE(box_contains(box, from_box_coordinates(box, {0.49, -0.49})));
  EXPECT_FALSE(box_contains(box, from_box_coordinates(box, {0.51, 0.0})));
}

// BoxFrame (one box, many points) against OpenCV's polygon test on the box's corners, on a grid of
// points around boxes at several angles; points within a hair of the outline are left out.
TEST(OrientedBox, BoxFrameAgreesWithThePolygonOfTheCorners) {
  for (const double angle : {-89.0, -35.0, 0.0, 12.5, 45.0, 90.0}) {
    const OrientedBox box{50.3, 40.7, 6.0, 15.0, angle};
    const BoxFrame frame(box);
    const auto corners = box_corners(box);
    const std::vector<cv::Point2f> polygon(corners.begin(), corners.end());
    int inside = 0;
    for (double y = 30.0; y <= 52.0; y += 0.37) {
      for (double x = 40.0; x <= 62.0; x += 0.37) {
        const double distance = cv::pointPolygonTest(polygon, cv::Point2f(static_cast<float>(x), static_cast<float>(y)), true);
        if (std::abs(distance) < 1e-3) continue;
        EXPECT_EQ(frame.contains({x, y}), distance > 0.0) << "angle " << angle << " at " << x << ", " << y;
        EXPECT_EQ(box_contains(box, {x, y}), frame.contains({x, y}));
        inside += frame.contains({x, y}) ? 1 : 0;
      }
    }
    EXPECT_NEAR(inside * 0.37 * 0.37, box_area(box), 0.1 * box_area(box));
  }
}

TEST(OrientedBox, DetectsNonFiniteValues) {
  EXPECT_TRUE(is_finite(OrientedBox{1, 2, 3, 4, 5}));
  EXPECT_FALSE(is_finite(OrientedBox{1, NAN, 3, 4, 5}));
}

}  // namespace
}  // namespace uavmot
