#include "uavmot/core/chain_types.hpp"

#include "uavmot/core/error.hpp"

namespace uavmot {

const char* to_string(SegmentationMethod method) {
  switch (method) {
    case SegmentationMethod::Clustering: return "clustering";
    case SegmentationMethod::Korn: return "korn";
    case SegmentationMethod::Morphological: return "morphological";
    case SegmentationMethod::Lbp: return "lbp";
    case SegmentationMethod::Fusion: return "fusion";
  }
  return "unknown";
}

const char* to_string(TrackState state) {
  switch (state) {
    case TrackState::Tentative: return "tentative";
    case TrackState::Confirmed: return "confirmed";
    case TrackState::Coasting: return "coasting";
  }
  return "unknown";
}

SegmentationMethod parse_segmentation_method(const std::string& name) {
  for (auto m : {SegmentationMethod::Clustering, SegmentationMethod::Korn, SegmentationMethod::Morphological,
                 SegmentationMethod::Lbp, SegmentationMethod::Fusion}) {
    if (name == to_string(m)) return m;
  }
  throw InvalidArgument("unknown segmentation method '" + name +
                        "' (expected clustering, korn, morphological, lbp or fusion)");
}

}  // namespace uavmot
