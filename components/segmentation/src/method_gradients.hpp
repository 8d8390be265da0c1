#pragma once
// What each segmentation method computes on a cluster's window (paper III-B): the one place a
// gradient method is defined. The methods themselves are listed once, in the enum SegmentationMethod
// of idl/segmentation.idl, which the build turns into core's list (uavmot/core/segmentation_method.hpp).

#include <opencv2/core/mat.hpp>

#include "uavmot/core/segmentation_method.hpp"
#include "uavmot/segmentation/segmentation_options.hpp"

namespace uavmot::segmentation {

// A gradient accumulator (CV_32F, any scale) of a grey window.
using Gradient = cv::Mat (*)(const cv::Mat& gray, const GradientOptions& options);

struct MethodGradient {
  // Null for clustering (no image: its regions are the clusters' boxes) and fusion (the fused
  // methods' accumulators, normalised and combined by regions.fusion_rule).
  Gradient gradient = nullptr;
  bool fused = false;    // one of fusion's accumulators
  int connectivity = 4;  // of its blobs when regions.connectivity is 0 (by method)
};

MethodGradient method_gradient(SegmentationMethod method);

}  // namespace uavmot::segmentation
