#pragma once
// The ground as one gray raster: a mosaic of real aerial images (feathered tiles), resampled
// to the rendering resolution, with asphalt, lane markings and parking lots painted on it.

#include <cstdint>
#include <string>

#include <opencv2/core/mat.hpp>
#include <opencv2/core/matx.hpp>

#include "road_network.hpp"
#include "uavmot/sim/scenario.hpp"

namespace uavmot::sim::detail {

struct GroundRaster {
  cv::Mat image;               // CV_8UC1
  cv::Point2d origin_m;        // world position of raster pixel (0, 0)
  double gsd_m = 1.0;          // metres per raster pixel
  // Raster px -> world metres.
  cv::Matx33d world_from_raster() const {
    return cv::Matx33d(gsd_m, 0, origin_m.x, 0, gsd_m, origin_m.y, 0, 0, 1);
  }
};

// Size of the raster covering region_m; throws InputError (naming ground.raster_max_megapixels)
// when it would be too large.
cv::Size checked_raster_size(const Scenario& scenario, cv::Rect2d region_m, double raster_gsd_m);

// Throws InputError when the texture folder is missing or holds no readable image, or when the
// raster would exceed ground.raster_max_megapixels.
GroundRaster build_ground_raster(const Scenario& scenario, const RoadNetwork& network, cv::Rect2d region_m,
                                 double raster_gsd_m, uint64_t seed);

}  // namespace uavmot::sim::detail
