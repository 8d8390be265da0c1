#include "uavmot/foxglove/messages.hpp"

namespace uavmot::foxglove {

Time time_from_ns(int64_t ns) {
  if (ns <= 0) return {};
  return {static_cast<uint32_t>(ns / 1000000000), static_cast<uint32_t>(ns % 1000000000)};
}

}  // namespace uavmot::foxglove
