#pragma once
// Checks shared by the converters of received samples (chain_convert.cpp, downlink_convert.cpp),
// so the full and the compact topics accept the same boxes and frame indices.

#include <cmath>
#include <cstdint>
#include <string>

#include "uavmot/core/oriented_box.hpp"

namespace uavmot::dds::detail {

// A box anyone could draw: finite, non-negative size, not absurdly large.
inline bool sane(const OrientedBox& b) {
  return is_finite(b) && b.width >= 0.0 && b.length >= 0.0 && b.width < 1e5 && b.length < 1e5 &&
         std::abs(b.cx) < 1e6 && std::abs(b.cy) < 1e6;
}

inline bool bad_index(int64_t index, std::string& why) {
  if (index >= 1) return false;
  why = "frame index " + std::to_string(index) + " < 1";
  return true;
}

}  // namespace uavmot::dds::detail
