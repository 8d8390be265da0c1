#pragma once
// Empty chain results of one frame of a stream, as the integration tests inject them on the wire
// (forged streams, hand-made ground traffic): the fields the sink and the downlink key on.

#include <cstdint>
#include <string>

#include "uavmot/core/chain_types.hpp"

namespace uavmot::testing {

inline MotionEstimate motion_of(const std::string& stream, int64_t k) {
  MotionEstimate m;
  m.stream_id = stream;
  m.frame_index = k;
  m.image_width = 640;
  m.image_height = 480;
  return m;
}

inline SegmentationResult segmentation_of(const std::string& stream, int64_t k) {
  SegmentationResult s;
  s.stream_id = stream;
  s.frame_index = k;
  return s;
}

inline TrackList tracks_of(const std::string& stream, int64_t k) {
  TrackList t;
  t.stream_id = stream;
  t.frame_index = k;
  return t;
}

}  // namespace uavmot::testing
