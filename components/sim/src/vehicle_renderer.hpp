#pragma once
// Draws vehicles and their shadows into a float image by 4x4 supersampling of each pixel
// through the exact vehicle->image homography, so edges are anti-aliased at true size, and
// marks each pixel that a vehicle covers by at least half in an id mask.

#include <vector>

#include <opencv2/core/mat.hpp>
#include <opencv2/core/matx.hpp>

#include "traffic.hpp"
#include "uavmot/core/oriented_box.hpp"

namespace uavmot::sim::detail {

struct ShadowParams {
  cv::Point2d offset_m;  // shadow displacement on the ground
  double strength = 0.45;
};

// image: CV_32F; id_mask: CV_32S receiving ids[i] for vehicles[i].
void render_vehicles(cv::Mat& image, cv::Mat& id_mask, const std::vector<const Vehicle*>& vehicles,
                     const std::vector<int>& ids, const cv::Matx33d& image_from_world, const ShadowParams& shadow);

// True footprint of a vehicle in the image (centre exact, axes through the projection).
OrientedBox image_box(const Vehicle& vehicle, const cv::Matx33d& image_from_world);

}  // namespace uavmot::sim::detail
