#include "record_places.hpp"

namespace uavmot::tracking {

void carry_places(TrackRecord& record, const Homography& h) {
  record.anchor_box = transform_box(h, record.anchor_box);
  record.origin = apply_homography(h, record.origin);
  record.travel_from = apply_homography(h, record.travel_from);
}

}  // namespace uavmot::tracking
