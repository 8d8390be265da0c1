#include "method_gradients.hpp"

#include "uavmot/segmentation/gradients.hpp"

namespace uavmot::segmentation {
namespace {

cv::Mat korn(const cv::Mat& gray, const GradientOptions& g) { return korn_gradient(gray, g.korn_sigmas_px); }

cv::Mat morphological(const cv::Mat& gray, const GradientOptions& g) {
  return morphological_gradient(gray, g.morphological_sizes_px);
}

cv::Mat lbp(const cv::Mat& gray, const GradientOptions& g) {
  return lbp_gradient(gray, g.lbp_neighbours, g.lbp_radii_px, g.lbp_min_stddev);
}

}  // namespace

// Registration: each method's accumulator above and its case here, in this one file; the list of
// methods comes from the IDL. A plain switch rather than a registry of static registrars: no
// initialisation order, one place to read, and no default, so a method added to the IDL without
// a case here does not compile (-Wswitch, an error with -Werror).
MethodGradient method_gradient(SegmentationMethod method) {
  switch (method) {
    case SegmentationMethod::Clustering: return {};
    case SegmentationMethod::Korn: return {korn, true, 4};
    case SegmentationMethod::Morphological: return {morphological, true, 4};
    // The LBP accumulator is sparse: accepted pixels often touch only diagonally.
    case SegmentationMethod::Lbp: return {lbp, true, 8};
    // 4-connected: 8 would leak across the thin diagonal gap between two cars side by side.
    case SegmentationMethod::Fusion: return {};
  }
  return {};
}

}  // namespace uavmot::segmentation
