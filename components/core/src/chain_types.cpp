#include "uavmot/core/chain_types.hpp"

#include <cmath>

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

namespace {
double to_float32(double v) { return static_cast<double>(static_cast<float>(v)); }
bool float32_exact(double v) { return to_float32(v) == v || std::isnan(v); }
}  // namespace

void round_to_float32(Track& t) {
  for (double* v : {&t.box.cx, &t.box.cy, &t.box.width, &t.box.length, &t.box.angle_deg, &t.velocity[0], &t.velocity[1]}) {
    *v = to_float32(*v);
  }
}

bool is_float32_exact(const Track& t) {
  return float32_exact(t.box.cx) && float32_exact(t.box.cy) && float32_exact(t.box.width) && float32_exact(t.box.length) &&
         float32_exact(t.box.angle_deg) && float32_exact(t.velocity[0]) && float32_exact(t.velocity[1]);
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
