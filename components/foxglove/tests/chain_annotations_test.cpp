// The chain's results as Foxglove annotations: boxes as closed polygons on their corners, ids and
// km/h as text, features as points with velocity vectors, uavmot-view's colours.

#include <gtest/gtest.h>

#include "uavmot/core/error.hpp"
#include "uavmot/core/oriented_box.hpp"
#include "uavmot/foxglove/chain_annotations.hpp"

namespace uavmot::foxglove {
namespace {

Track make_track(uint64_t id, TrackState state, const OrientedBox& box, cv::Vec2d velocity) {
  Track t;
  t.id = id;
  t.state = state;
  t.box = box;
  t.velocity = velocity;
  return t;
}

TEST(ChainAnnotations, ConfirmedTrackIsAGreenPolygonWithIdAndSpeed) {
  TrackList list;
  list.capture_time_ns = 2'500'000'000;
  const OrientedBox box{100.0, 50.0, 4.0, 10.0, 30.0};
  list.tracks.push_back(make_track(7, TrackState::Confirmed, box, {1.0, 0.0}));
  const auto a = annotate_tracks(list, {.gsd_m = 0.5, .fps = 25.0});
  ASSERT_EQ(a.points.size(), 1u);
  const auto& polygon = a.points[0];
  EXPECT_EQ(polygon.type, PointsType::LineLoop);
  EXPECT_EQ(polygon.timestamp.sec, 2u);
  EXPECT_EQ(polygon.timestamp.nsec, 500'000'000u);
  const auto corners = box_corners(box);
  ASSERT_EQ(polygon.points.size(), 4u);
  for (size_t i = 0; i < 4; ++i) {
    EXPECT_DOUBLE_EQ(polygon.points[i].x, corners[i].x);
    EXPECT_DOUBLE_EQ(polygon.points[i].y, corners[i].y);
  }
  EXPECT_EQ(polygon.outline_color.g, 1.0);
  EXPECT_EQ(polygon.outline_color.r, 0.0);
  EXPECT_EQ(polygon.fill_color.a, 0.0);  // outline only: the vehicle stays visible
  ASSERT_EQ(a.texts.size(), 1u);
  EXPECT_EQ(a.texts[0].text, "#7 45 km/h");  // 1 px/frame * 0.5 m/px * 25 /s * 3.6
  EXPECT_LT(a.texts[0].position.y, box.cy);  // above the box
  EXPECT_TRUE(a.circles.empty());
}

TEST(ChainAnnotations, WithoutGsdSpeedIsInPixelsPerFrame) {
  TrackList list;
  list.tracks.push_back(make_track(3, TrackState::Coasting, {10, 10, 2, 4, 0}, {0.0, 1.2}));
  const auto a = annotate_tracks(list, {});
  ASSERT_EQ(a.texts.size(), 1u);
  EXPECT_EQ(a.texts[0].text, "#3 1.2 px/f");
  EXPECT_LT(a.points[0].outline_color.a, 1.0);  // coasting: faded
}

TEST(ChainAnnotations, TentativeTracksHaveNoLabelAndCanBeHidden) {
  TrackList list;
  list.tracks.push_back(make_track(1, TrackState::Tentative, {10, 10, 2, 4, 0}, {0, 0}));
  EXPECT_EQ(annotate_tracks(list, {}).points.size(), 1u);
  EXPECT_TRUE(annotate_tracks(list, {}).texts.empty());
  EXPECT_TRUE(annotate_tracks(list, {.tentative_tracks = false}).points.empty());
}

TEST(ChainAnnotations, RegionsRedAndClustersCyan) {
  SegmentationResult s;
  s.clusters.push_back({1, {20, 20, 5, 9, 10}, {0, 0}, {}});
  s.regions.push_back({{21, 21, 4, 8, 12}, SegmentationMethod::Fusion, 0.9, 1});
  s.regions.push_back({{60, 60, 4, 8, 0}, SegmentationMethod::Korn, 0.5, -1});
  const auto a = annotate_segmentation(s);
  ASSERT_EQ(a.points.size(), 3u);
  EXPECT_EQ(a.points[0].outline_color.b, 1.0);  // cyan
  EXPECT_EQ(a.points[0].outline_color.g, 1.0);
  EXPECT_EQ(a.points[1].outline_color.r, 1.0);  // red
  EXPECT_EQ(a.points[1].outline_color.g, 0.0);
  for (const auto& p : a.points) EXPECT_EQ(p.type, PointsType::LineLoop);
}

TEST(ChainAnnotations, MovingFeaturesArePointsWithVelocityVectors) {
  MotionEstimate m;
  TrackedFeature moving{1, {10, 20}, {1, -2}, 0.1, 5, true};
  TrackedFeature still{2, {30, 40}, {0, 0}, 0.1, 5, false};
  m.features = {moving, still};
  const auto a = annotate_motion(m, {.vector_scale = 10.0});
  ASSERT_EQ(a.points.size(), 2u);  // moving points, their vectors; stationary ones not asked for
  EXPECT_EQ(a.points[0].type, PointsType::Points);
  ASSERT_EQ(a.points[0].points.size(), 1u);
  EXPECT_EQ(a.points[1].type, PointsType::LineList);
  ASSERT_EQ(a.points[1].points.size(), 2u);
  EXPECT_DOUBLE_EQ(a.points[1].points[1].x, 20.0);
  EXPECT_DOUBLE_EQ(a.points[1].points[1].y, 0.0);
  EXPECT_EQ(annotate_motion(m, {.stationary_features = true}).points.size(), 3u);
  EXPECT_TRUE(annotate_motion(MotionEstimate{}, {}).points.empty());
}

TEST(ChainAnnotations, RawImageCopiesRowsWithoutPadding) {
  cv::Mat big(4, 6, CV_8UC3);
  for (int i = 0; i < big.rows * big.cols * 3; ++i) big.data[i] = static_cast<uint8_t>(i);
  Frame f{"uav1", 3, 1'000'000'001, big(cv::Rect(1, 1, 3, 2))};  // a view: rows are not contiguous
  const auto raw = raw_image(f);
  EXPECT_EQ(raw.width, 3u);
  EXPECT_EQ(raw.height, 2u);
  EXPECT_EQ(raw.step, 9u);
  EXPECT_EQ(raw.encoding, "bgr8");
  EXPECT_EQ(raw.frame_id, "uav1");
  ASSERT_EQ(raw.data.size(), 18u);
  EXPECT_EQ(raw.data[0], big.at<cv::Vec3b>(1, 1)[0]);
  EXPECT_EQ(raw.data[9], big.at<cv::Vec3b>(2, 1)[0]);
  EXPECT_EQ(raw.timestamp.nsec, 1u);
}

TEST(ChainAnnotations, JpegImageDecodesToTheFrame) {
  cv::Mat gray(48, 64, CV_8UC1, cv::Scalar(128));
  const auto jpeg = jpeg_image(Frame{"uav1", 1, 0, gray}, 90);
  EXPECT_EQ(jpeg.format, "jpeg");
  ASSERT_GT(jpeg.data.size(), 2u);
  EXPECT_EQ(jpeg.data[0], 0xff);
  EXPECT_EQ(jpeg.data[1], 0xd8);
  EXPECT_THROW(jpeg_image(Frame{"uav1", 1, 0, cv::Mat()}, 90), InputError);
}

TEST(ChainAnnotations, ImageFormatNames) {
  EXPECT_EQ(parse_image_format("jpeg"), ImageFormat::Jpeg);
  EXPECT_EQ(parse_image_format("raw"), ImageFormat::Raw);
  EXPECT_THROW(parse_image_format("png"), InvalidArgument);
}

}  // namespace
}  // namespace uavmot::foxglove
