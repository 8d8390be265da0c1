#include "../src/feature_recentring.hpp"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

namespace uavmot::segmentation {
namespace {

// A box 6 px wide heading along +x; its centre line is y = 50.
const OrientedBox kBox{100.0, 50.0, 6.0, 15.0, 0.0};

TEST(FeatureRecentring, FeaturesWithinTheGrownBox) {
  const auto inside = features_within(kBox, 1.5, {{100.0, 50.0}, {107.0, 54.4}, {109.5, 50.0}, {100.0, 55.0}});
  ASSERT_EQ(inside.size(), 2u);  // 7.5 + 1.5 px along, 3 + 1.5 px across
  EXPECT_EQ(inside[1], cv::Point2d(107.0, 54.4));
}

TEST(FeatureRecentring, MeanOffsetIsAcrossTheHeadingOnly) {
  EXPECT_DOUBLE_EQ(mean_offset_across(kBox, {{90.0, 52.0}, {110.0, 54.0}}), 3.0);  // along x does not count
  OrientedBox turned = kBox;
  turned.angle_deg = 90.0;  // heading +y: across is -x
  EXPECT_NEAR(mean_offset_across(turned, {{98.0, 40.0}, {98.0, 60.0}}), 2.0, 1e-12);
  EXPECT_EQ(mean_offset_across(kBox, {}), 0.0);
}

TEST(FeatureRecentring, ABoxBesideItsFeaturesMovesAcrossOntoThem) {
  // Features 2 px below the centre line (1/3 of the width): beyond 0.2 widths.
  const OrientedBox moved = recentred_on_features(kBox, {{95.0, 52.0}, {105.0, 52.0}}, 0.2);
  EXPECT_NEAR(moved.cx, 100.0, 1e-12);  // not along the heading
  EXPECT_NEAR(moved.cy, 52.0, 1e-12);
  EXPECT_EQ(moved.width, kBox.width);
  EXPECT_EQ(moved.length, kBox.length);
  EXPECT_EQ(moved.angle_deg, kBox.angle_deg);
  // At 45 deg the move is along the normal (-sin, cos).
  OrientedBox diagonal = kBox;
  diagonal.angle_deg = 45.0;
  const double s = std::sqrt(0.5);
  const OrientedBox moved_diagonal = recentred_on_features(diagonal, {{100.0 - 2.0 * s, 50.0 + 2.0 * s}, {100.0 - 2.0 * s + 3.0 * s, 50.0 + 2.0 * s + 3.0 * s}}, 0.2);
  EXPECT_NEAR(moved_diagonal.cx, 100.0 - 2.0 * s, 1e-9);
  EXPECT_NEAR(moved_diagonal.cy, 50.0 + 2.0 * s, 1e-9);
}

TEST(FeatureRecentring, CentredFeaturesOneFeatureOrDisabledLeaveTheBox) {
  EXPECT_EQ(recentred_on_features(kBox, {{95.0, 51.0}, {105.0, 50.5}}, 0.2), kBox);  // 0.75 px < 1.2 px
  EXPECT_EQ(recentred_on_features(kBox, {{95.0, 53.0}}, 0.2), kBox);                 // one feature
  EXPECT_EQ(recentred_on_features(kBox, {{95.0, 53.0}, {105.0, 53.0}}, 0.0), kBox);   // off
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(recentred_on_features(kBox, {{nan, 53.0}, {105.0, 53.0}}, 0.2), kBox);
}

}  // namespace
}  // namespace uavmot::segmentation
