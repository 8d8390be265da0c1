// draw_overlay puts each layer's colour where its geometry is, and nowhere else.

#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include "uavmot/core/error.hpp"
#include "uavmot/core/oriented_box.hpp"
#include "uavmot/view/overlay.hpp"

namespace uavmot::view {
namespace {

const cv::Mat kBlack(200, 200, CV_8UC1, cv::Scalar(0));

// A drawn pixel of `colour` on black: full channels clearly lit, empty channels clearly dark
// (anti-aliased edges are dimmer but keep the hue).
bool has_colour(const cv::Mat& image, cv::Point2d p, const cv::Scalar& colour, int min_lit = 90) {
  const cv::Vec3b px = image.at<cv::Vec3b>(cv::Point(static_cast<int>(std::lround(p.x)), static_cast<int>(std::lround(p.y))));
  const int brightest = std::max({px[0], px[1], px[2]});
  if (brightest < min_lit) return false;
  for (int c = 0; c < 3; ++c) {
    const bool lit = colour[c] > 0;
    if (lit && px[c] < 0.75 * brightest) return false;
    if (!lit && px[c] > 0.35 * brightest) return false;
  }
  return true;
}

bool is_black_around(const cv::Mat& image, cv::Point p, int radius) {
  for (int y = p.y - radius; y <= p.y + radius; ++y) {
    for (int x = p.x - radius; x <= p.x + radius; ++x) {
      if (image.at<cv::Vec3b>(y, x) != cv::Vec3b(0, 0, 0)) return false;
    }
  }
  return true;
}

OverlayOptions plain() {
  OverlayOptions o;
  o.frame_label = false;
  return o;
}

Track track_at(const OrientedBox& box, TrackState state, cv::Vec2d velocity = {0, 0}) {
  Track t;
  t.id = 7;
  t.state = state;
  t.box = box;
  t.velocity = velocity;
  return t;
}

cv::Point2d midpoint(const cv::Point2d& a, const cv::Point2d& b) { return (a + b) * 0.5; }

TEST(Overlay, ConfirmedTrackIsAGreenOutlineAtItsBox) {
  TrackList tracks;
  tracks.frame_index = 3;
  const OrientedBox box{100, 110, 40, 60, 0};  // x 70..130, y 90..130
  tracks.tracks.push_back(track_at(box, TrackState::Confirmed));
  const cv::Mat out = draw_overlay(kBlack, nullptr, nullptr, &tracks, plain());
  ASSERT_EQ(out.type(), CV_8UC3);
  ASSERT_EQ(out.size(), kBlack.size());
  EXPECT_TRUE(has_colour(out, {100, 90}, kConfirmedTrackColour));   // top edge
  EXPECT_TRUE(has_colour(out, {100, 130}, kConfirmedTrackColour));  // bottom edge
  EXPECT_TRUE(has_colour(out, {70, 110}, kConfirmedTrackColour));   // left edge
  EXPECT_TRUE(has_colour(out, {130, 110}, kConfirmedTrackColour));  // right edge
  EXPECT_TRUE(is_black_around(out, {100, 110}, 12));                // inside, away from the edges
  EXPECT_TRUE(is_black_around(out, {170, 175}, 10));                // outside
}

TEST(Overlay, RotatedBoxesFollowTheirCorners) {
  SegmentationResult seg;
  seg.frame_index = 1;
  Region region;
  region.box = OrientedBox{100, 100, 30, 80, 30};
  seg.regions.push_back(region);
  const cv::Mat out = draw_overlay(kBlack, nullptr, &seg, nullptr, plain());
  const auto c = box_corners(region.box);
  for (size_t i = 0; i < 4; ++i) {
    EXPECT_TRUE(has_colour(out, midpoint(c[i], c[(i + 1) % 4]), kRegionColour)) << "edge " << i;
  }
  EXPECT_TRUE(is_black_around(out, {100, 100}, 8));
  // An axis-aligned box of the same size would have its corner here; the rotated one does not.
  EXPECT_TRUE(is_black_around(out, {140, 85}, 2));
}

TEST(Overlay, ClustersAreCyanRegionsRed) {
  SegmentationResult seg;
  FeatureCluster cluster;
  cluster.box = OrientedBox{50, 50, 20, 30, 0};  // x 35..65, y 40..60
  seg.clusters.push_back(cluster);
  Region region;
  region.box = OrientedBox{150, 150, 20, 30, 90};  // length along y: x 140..160, y 135..165
  seg.regions.push_back(region);
  const cv::Mat out = draw_overlay(kBlack, nullptr, &seg, nullptr, plain());
  EXPECT_TRUE(has_colour(out, {50, 40}, kClusterColour));
  EXPECT_TRUE(has_colour(out, {35, 50}, kClusterColour));
  EXPECT_FALSE(has_colour(out, {35, 50}, kRegionColour));
  EXPECT_TRUE(has_colour(out, {140, 150}, kRegionColour));
  EXPECT_TRUE(has_colour(out, {150, 135}, kRegionColour));
  EXPECT_FALSE(has_colour(out, {150, 135}, kClusterColour));
  EXPECT_TRUE(is_black_around(out, {100, 100}, 20));

  OverlayOptions no_clusters = plain();
  no_clusters.clusters = false;
  const cv::Mat without = draw_overlay(kBlack, nullptr, &seg, nullptr, no_clusters);
  EXPECT_TRUE(is_black_around(without, {50, 40}, 2));
  EXPECT_TRUE(has_colour(without, {140, 150}, kRegionColour));
}

TEST(Overlay, MovingFeatureIsAYellowVectorScaledFromItsPosition) {
  MotionEstimate motion;
  TrackedFeature moving;
  moving.position = {30, 150};
  moving.velocity = {2.0, 0.0};  // x10 -> an arrow from x 30 to x 50
  moving.moving = true;
  TrackedFeature still;
  still.position = {150, 30};
  still.moving = false;
  motion.features = {moving, still};
  const cv::Mat out = draw_overlay(kBlack, &motion, nullptr, nullptr, plain());
  for (int x = 31; x <= 45; ++x) EXPECT_TRUE(has_colour(out, {double(x), 150}, kMovingFeatureColour)) << x;
  EXPECT_TRUE(is_black_around(out, {60, 150}, 4));   // it ends at the scaled tip
  EXPECT_TRUE(is_black_around(out, {20, 150}, 4));   // and starts at the feature
  EXPECT_TRUE(is_black_around(out, {150, 30}, 3));   // stationary features are off by default

  OverlayOptions with_stationary = plain();
  with_stationary.stationary_features = true;
  with_stationary.vector_scale = 5.0;
  const cv::Mat both = draw_overlay(kBlack, &motion, nullptr, nullptr, with_stationary);
  EXPECT_TRUE(has_colour(both, {150, 30}, kStationaryFeatureColour));
  EXPECT_TRUE(has_colour(both, {36, 150}, kMovingFeatureColour));
  EXPECT_TRUE(is_black_around(both, {48, 150}, 2));  // x5: the arrow now ends at x 40
}

TEST(Overlay, TrackStatesAreDistinguishable) {
  TrackList tracks;
  tracks.tracks.push_back(track_at(OrientedBox{50, 100, 20, 60, 0}, TrackState::Tentative));  // x 20..80, y 90..110
  tracks.tracks.push_back(track_at(OrientedBox{150, 100, 20, 80, 0}, TrackState::Coasting));  // x 110..190
  const cv::Mat out = draw_overlay(kBlack, nullptr, nullptr, &tracks, plain());
  // Tentative: dim green, thin.
  const cv::Vec3b tentative = out.at<cv::Vec3b>(90, 50);
  EXPECT_GT(tentative[1], 60);
  EXPECT_LE(tentative[1], 150);
  EXPECT_LT(tentative[2], 30);
  // Coasting: dashed, so the top edge has both green and dark stretches.
  int lit = 0, dark = 0;
  for (int x = 112; x <= 188; ++x) (out.at<cv::Vec3b>(90, x)[1] > 150 ? lit : dark) += 1;
  EXPECT_GT(lit, 15);
  EXPECT_GT(dark, 15);

  OverlayOptions hide = plain();
  hide.tentative_tracks = false;
  EXPECT_TRUE(is_black_around(draw_overlay(kBlack, nullptr, nullptr, &tracks, hide), {50, 90}, 2));
}

TEST(Overlay, ScaleEnlargesTheFrameAndKeepsGeometryInPlace) {
  TrackList tracks;
  tracks.tracks.push_back(track_at(OrientedBox{100, 110, 40, 60, 0}, TrackState::Confirmed));
  OverlayOptions options = plain();
  options.scale = 2.0;
  const cv::Mat out = draw_overlay(kBlack, nullptr, nullptr, &tracks, options);
  ASSERT_EQ(out.size(), cv::Size(400, 400));
  // Continuous x 70 -> (70 + 0.5) * 2 - 0.5 = 140.5 in the output.
  EXPECT_TRUE(has_colour(out, {140.5, 220}, kConfirmedTrackColour));
  EXPECT_TRUE(has_colour(out, {200, 180.5}, kConfirmedTrackColour));  // top: (90.5) * 2 - 0.5
  EXPECT_TRUE(is_black_around(out, {200, 220}, 25));
}

TEST(Overlay, LabelsAreWrittenNearTheirObject) {
  TrackList tracks;
  tracks.frame_index = 5;
  tracks.tracks.push_back(track_at(OrientedBox{100, 150, 20, 40, 0}, TrackState::Confirmed, {1, 0}));
  OverlayOptions options;  // with the frame label
  const cv::Mat out = draw_overlay(kBlack, nullptr, nullptr, &tracks, options);
  // The id/speed label sits just above the box (y < 140), in green; the frame label top-left, white.
  int green_above = 0;
  for (int y = 110; y < 139; ++y) {
    for (int x = 60; x < 200; ++x) green_above += has_colour(out, {double(x), double(y)}, kConfirmedTrackColour, 150);
  }
  EXPECT_GT(green_above, 10);
  int white_top_left = 0;
  for (int y = 0; y < 25; ++y) {
    for (int x = 0; x < 120; ++x) {
      const cv::Vec3b px = out.at<cv::Vec3b>(y, x);
      white_top_left += px[0] > 180 && px[1] > 180 && px[2] > 180;
    }
  }
  EXPECT_GT(white_top_left, 10);
}

TEST(Overlay, KeepsTheInputAndIgnoresNonFiniteGeometry) {
  cv::Mat frame(50, 60, CV_8UC3, cv::Scalar(10, 20, 30));
  const cv::Mat copy = frame.clone();
  TrackList tracks;
  tracks.tracks.push_back(track_at(OrientedBox{std::nan(""), 10, 5, 5, 0}, TrackState::Confirmed));
  const cv::Mat out = draw_overlay(frame, nullptr, nullptr, &tracks, plain());
  EXPECT_EQ(cv::norm(frame, copy, cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(out, copy, cv::NORM_INF), 0.0);
  EXPECT_THROW(draw_overlay(cv::Mat(), nullptr, nullptr, nullptr, plain()), InvalidArgument);
}

TEST(FormatSpeed, KilometresPerHourWhenTheGsdIsKnown) {
  // |(3, 4)| = 5 px/frame * 0.2 m/px * 25 fps = 25 m/s = 90 km/h.
  EXPECT_EQ(format_speed({3, 4}, 0.2, 25.0), "90 km/h");
  EXPECT_EQ(format_speed({0.5, 0}, 0.3, 30.0), "16 km/h");  // 4.5 m/s = 16.2 km/h
  EXPECT_EQ(format_speed({3, 4}, 0.0, 25.0), "5.0 px/f");
  EXPECT_EQ(format_speed({std::nan(""), 0}, 0.2, 25.0), "?");
}

TEST(FormatFrameLabel, FrameAndTimeFromTheFirstFrame) {
  EXPECT_EQ(format_frame_label(26, 25.0), "frame 26  1.00 s");
  EXPECT_EQ(format_frame_label(1, 25.0), "frame 1  0.00 s");
  EXPECT_EQ(format_frame_label(3, 0.0), "frame 3");
}

}  // namespace
}  // namespace uavmot::view
