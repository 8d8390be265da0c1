#pragma once
// The part of a frame that holds picture. Analogue capture and letterboxing leave black bands at
// the image's edges (the aphill FMV: 4-8 px columns at both sides, a row at the bottom). The band's
// inner edge is fixed in the image: a corner there, its LK window half band and half ground,
// follows neither the ground nor a vehicle, and at the camera's speed it reads as a mover at the
// border. Features keep border_px inside this area instead of inside the image.

#include <opencv2/core/mat.hpp>
#include <opencv2/core/types.hpp>

#include "uavmot/motion/motion_options.hpp"

namespace uavmot::motion {

// The rectangle of `gray` (CV_8UC1) inside its black bands: from each edge inward, the lines (rows
// or columns) whose mean grey is at most blank_band_max_grey and whose brightest pixel is at most 4
// times that are band, at most an eighth of the side on each edge, and where there is a band, 2
// lines more (its soft edge). The whole image when blank_band_max_grey is 0 or there is no band.
cv::Rect active_picture_area(const cv::Mat& gray, const MotionOptions& options);

// `picture` less `border_px` on every side (may be empty).
cv::Rect usable_area(const cv::Rect& picture, int border_px);

}  // namespace uavmot::motion
