#pragma once
// Textures of the static structures, made once per structure from its own seed: roofs with a
// parapet and rooftop units, facades with rows of windows, dark high-frequency foliage. Each
// has corners and fine detail, as real roofs and trees do, so feature trackers lock on them
// (which is what makes their parallax a false-alarm risk worth simulating).

#include <cstdint>

#include <opencv2/core/mat.hpp>

#include "structure_layout.hpp"

namespace uavmot::sim::detail {

// Texture pixel size on every structure face.
constexpr double kStructureTexelM = 0.15;

// Roof of a building or top of a wall: length_m x width_m, row = across, column = along.
cv::Mat roof_texture(const Structure& s);
// One side of a building or wall, `length_m` wide and height_m tall, row 0 at the top; `gain`
// is the sun shading of that side.
cv::Mat facade_texture(const Structure& s, double length_m, double gain, int side);
// Canopy seen from above, 2 x canopy_radius_m square centred on the trunk.
cv::Mat canopy_texture(const Structure& s, cv::Point2d sun_direction);

}  // namespace uavmot::sim::detail
