#pragma once
// Shi-Tomasi's corner response, the smaller eigenvalue of each pixel's gradient covariance, in
// cv::cornerMinEigenVal(gray, eig, block, 3)'s units (3x3 Sobel scaled by 1 / (4 block 255), block
// sums, reflected borders), computed exactly: the Sobel products and their block sums in integers,
// the eigenvalue from those sums in double. A pixel's value therefore depends on its neighbourhood
// only, never on which region computed it (cornerMinEigenVal's float sums differ in the last bits
// between a cell's region and the whole frame), and most pixels of the cells the corner search
// visits, flat ground and plain edges, are settled in integers without a square root. It replaced
// an integer bound that passed cells over before cornerMinEigenVal: the same corners, 45 % fewer
// instructions in the corner search (docs/benchmarks/process.md).

#include <opencv2/core/mat.hpp>

namespace uavmot::motion {

// The response of every pixel of `region` (inside the 8-bit grey image) into `out` (CV_32F,
// region's size). Values that cannot reach `floor` are stored as 0, which spares the square root
// where the image is flat; a corner search with a threshold >= floor finds the same corners as
// with the exact values (a pixel above the threshold is never below a neighbour that is under it).
void min_eigen_values(const cv::Mat& gray, const cv::Rect& region, int block, double floor, cv::Mat& out);

}  // namespace uavmot::motion
