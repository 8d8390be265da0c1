#include "uavmot/geo/frame_geometry.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>

#include <gtest/gtest.h>

#include "test_data.hpp"
#include "uavmot/core/error.hpp"
#include "uavmot/geo/misb0601.hpp"
#include "uavmot/geo/mpegts_klv.hpp"

namespace uavmot::geo {
namespace {

const cv::Size kAphillSize(720, 480);

UasMetadata aphill_packet(std::size_t index) {
  const MpegTsKlv ts = read_mpegts_klv(test::aphill_ts_path());
  return *decode_uas_metadata(ts.klv.at(index).bytes);
}

TEST(FrameGeometry, ImageCornersMapToThePacketCorners) {
  const UasMetadata m = aphill_packet(0);
  const FrameGeometry g = FrameGeometry::from_metadata(m, kAphillSize);
  ASSERT_TRUE(g.has_ground_mapping());
  const auto image = image_corners(kAphillSize);
  EXPECT_EQ(image[0], cv::Point2d(-0.5, -0.5));    // corner 1: upper left
  EXPECT_EQ(image[2], cv::Point2d(719.5, 479.5));  // corner 3: lower right
  for (std::size_t i = 0; i < 4; ++i) {
    const auto p = g.pixel_to_lat_lon(image[i]);
    ASSERT_TRUE(p);
    EXPECT_NEAR(p->lat_deg, *m.corner_latitude_deg[i], 1e-10) << "corner " << i + 1;
    EXPECT_NEAR(p->lon_deg, *m.corner_longitude_deg[i], 1e-10) << "corner " << i + 1;
    const auto back = g.lat_lon_to_pixel({*m.corner_latitude_deg[i], *m.corner_longitude_deg[i]});
    ASSERT_TRUE(back);
    EXPECT_NEAR(back->x, image[i].x, 1e-6);
    EXPECT_NEAR(back->y, image[i].y, 1e-6);
  }
}

TEST(FrameGeometry, PixelLatLonRoundTrip) {
  const FrameGeometry g = FrameGeometry::from_metadata(aphill_packet(10), kAphillSize);
  for (double y = -0.5; y <= 479.5; y += 53.0) {
    for (double x = -0.5; x <= 719.5; x += 61.0) {
      const auto ll = g.pixel_to_lat_lon({x, y});
      ASSERT_TRUE(ll);
      const auto px = g.lat_lon_to_pixel(*ll);
      ASSERT_TRUE(px);
      EXPECT_NEAR(px->x, x, 1e-6);
      EXPECT_NEAR(px->y, y, 1e-6);
    }
  }
}

TEST(FrameGeometry, AphillGsdIsPhysicallyPlausible) {
  const UasMetadata m = aphill_packet(0);
  const FrameGeometry g = FrameGeometry::from_metadata(m, kAphillSize);
  ASSERT_EQ(g.gsd_source(), GsdSource::kFootprint);
  const double range_fov = 2.0 * *m.slant_range_m * std::tan(*m.sensor_hfov_deg * std::numbers::pi / 360.0) / 720.0;
  const double depression = std::abs(*m.sensor_obliquity_deg) * std::numbers::pi / 180.0;
  std::printf("aphill packet 0: GSD %.4f m/px (footprint; x %.4f, y %.4f), slant range %.1f m x HFOV %.2f deg -> %.4f m/px, "
              "obliquity %.1f deg\n",
              *g.gsd_m_per_px(), *g.gsd_x_m_per_px(), *g.gsd_y_m_per_px(), *m.slant_range_m, *m.sensor_hfov_deg, range_fov,
              *m.sensor_obliquity_deg);
  // Across the line of sight the footprint and slant range x HFOV must agree (the packet's
  // corners came from the same camera model)...
  EXPECT_NEAR(*g.gsd_x_m_per_px(), range_fov, 0.05 * range_fov);
  // ...along it a row spans slant range x (VFOV / 480) on a plane facing the camera, stretched by
  // 1 / sin(depression) on the ground.
  const double along = *m.slant_range_m * (*m.sensor_vfov_deg * std::numbers::pi / 180.0 / 480.0) / std::sin(depression);
  EXPECT_NEAR(*g.gsd_y_m_per_px(), along, 0.1 * along);
  // A 1.7 km oblique shot through a 0.8 deg lens: centimetres per pixel.
  EXPECT_GT(*g.gsd_m_per_px(), 0.02);
  EXPECT_LT(*g.gsd_m_per_px(), 0.1);
  // The image centre lands within a few metres of the packet's frame centre.
  const auto center = g.pixel_to_lat_lon(image_center(kAphillSize));
  ASSERT_TRUE(center);
  EXPECT_LT(ground_distance_m(*center, *g.frame_center()), 3.0);
}

TEST(FrameGeometry, CentrePlusOffsetsWhenNoFullCorners) {
  UasMetadata m = decode_st0601(test::from_hex(test::kHandMade0601Hex));
  for (auto& c : m.corner_latitude_deg) c.reset();
  const auto corners = ground_corners(m);
  ASSERT_TRUE(corners);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_DOUBLE_EQ((*corners)[i].lat_deg, *m.frame_center_latitude_deg + *m.offset_corner_latitude_deg[i]);
    EXPECT_DOUBLE_EQ((*corners)[i].lon_deg, *m.frame_center_longitude_deg + *m.offset_corner_longitude_deg[i]);
  }
  const FrameGeometry g = FrameGeometry::from_metadata(m, {640, 480});
  EXPECT_EQ(g.gsd_source(), GsdSource::kFootprint);
  const auto p = g.pixel_to_lat_lon({-0.5, -0.5});
  ASSERT_TRUE(p);
  EXPECT_NEAR(p->lat_deg, (*corners)[0].lat_deg, 1e-10);
}

TEST(FrameGeometry, GsdFallsBackToSlantRangeThenTargetWidth) {
  UasMetadata m;
  m.slant_range_m = 1000.0;
  m.sensor_hfov_deg = 10.0;
  m.target_width_m = 300.0;
  const FrameGeometry a = FrameGeometry::from_metadata(m, {1000, 500});
  EXPECT_EQ(a.gsd_source(), GsdSource::kSlantRangeFov);
  EXPECT_DOUBLE_EQ(*a.gsd_m_per_px(), 2.0 * 1000.0 * std::tan(5.0 * std::numbers::pi / 180.0) / 1000.0);
  EXPECT_FALSE(a.has_ground_mapping());
  EXPECT_FALSE(a.pixel_to_lat_lon({1, 1}));

  m.sensor_hfov_deg.reset();
  const FrameGeometry b = FrameGeometry::from_metadata(m, {1000, 500});
  EXPECT_EQ(b.gsd_source(), GsdSource::kTargetWidth);
  EXPECT_DOUBLE_EQ(*b.gsd_m_per_px(), 0.3);

  m.target_width_m.reset();
  EXPECT_EQ(FrameGeometry::from_metadata(m, {1000, 500}).gsd_source(), GsdSource::kNone);
  EXPECT_THROW(FrameGeometry::from_metadata(m, {0, 500}), InvalidArgument);
}

TEST(FrameGeometry, DegenerateCornersGiveNoMapping) {
  UasMetadata m;
  for (std::size_t i = 0; i < 4; ++i) {
    m.corner_latitude_deg[i] = 38.0;
    m.corner_longitude_deg[i] = -77.0;
  }
  m.slant_range_m = 1000.0;
  m.sensor_hfov_deg = 1.0;
  const FrameGeometry g = FrameGeometry::from_metadata(m, {720, 480});
  EXPECT_FALSE(g.has_ground_mapping());
  EXPECT_EQ(g.gsd_source(), GsdSource::kSlantRangeFov);

  m.corner_latitude_deg[2] = 123.0;  // out of range
  EXPECT_FALSE(ground_corners(m));
}

}  // namespace
}  // namespace uavmot::geo
