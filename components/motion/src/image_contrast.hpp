#pragma once
// How strong the edges of a frame are: low-contrast imagery (haze, a dim sensor, dark cars on dark
// asphalt) gives every corner a weaker Shi-Tomasi response, so an absolute response threshold that
// suits a clear image finds no corner on its vehicles.

#include <opencv2/core/mat.hpp>

namespace uavmot::motion {

// The `percentile` (0-100) of the gradient magnitude of `gray` (CV_8UC1), in grey levels per pixel
// (central differences halved, rounded down to half levels), over every `row_step`-th row and every
// second column: a strong edge's height, not its count. 0 for an image smaller than 3 x 3 or not
// CV_8UC1.
double gradient_percentile(const cv::Mat& gray, double percentile, int row_step);

// The factor on min_corner_response for a frame whose gradient_percentile is `contrast`: the
// response grows with the square of the contrast, so (contrast / reference)^2, within
// [min_scale, 1]. 1 when reference <= 0 (off).
double corner_response_scale(double contrast, double reference, double min_scale);

}  // namespace uavmot::motion
