#pragma once
// Closing and hole filling of one blob's small 0/255 mask without OpenCV's per-call overhead.
// A frame has hundreds of blobs of a few hundred pixels each; for those, cv::morphologyEx,
// cv::findContours and cv::drawContours cost more in set-up (filter engines, contour storage,
// parallel dispatch) than in work. Both functions give exactly what the OpenCV calls give
// (components/segmentation/tests/binary_mask_test.cpp compares them on random masks).

#include <opencv2/core.hpp>

namespace uavmot::segmentation {

// cv::morphologyEx(mask, mask, MORPH_CLOSE, a size x size rectangle) with OpenCV's default
// borders (nothing outside the mask dilates, nothing outside erodes). `size` odd.
void close_binary(cv::Mat& mask, int size);

// Sets every 0 pixel that is not 4-connected to the mask's border: what drawing the external
// contours of the 8-connected foreground filled does.
void fill_holes(cv::Mat& mask);

}  // namespace uavmot::segmentation
