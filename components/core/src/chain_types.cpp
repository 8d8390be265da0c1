#include "uavmot/core/chain_types.hpp"

#include <cmath>


namespace uavmot {

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

}  // namespace uavmot
