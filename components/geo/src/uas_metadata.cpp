#include "uavmot/geo/uas_metadata.hpp"

#include <algorithm>

#include "uavmot/geo/eg0104.hpp"
#include "uavmot/geo/misb0601.hpp"

namespace uavmot::geo {

namespace {

template <typename Key>
bool has_key(Bytes unit, const Key& key) {
  return unit.size() >= key.size() && std::equal(key.begin(), key.end(), unit.begin());
}

}  // namespace

std::optional<UasMetadata> decode_uas_metadata(Bytes klv_unit) {
  if (has_key(klv_unit, kSt0601Key)) return decode_st0601(klv_unit);
  if (has_key(klv_unit, kEg0104Key)) return decode_eg0104(klv_unit);
  return std::nullopt;
}

}  // namespace uavmot::geo
