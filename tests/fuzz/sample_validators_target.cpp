// Fuzz target: arbitrary bytes as a CDR sample of each chain topic, then the receive-side validation.
// Whatever arrives on the wire, deserialization and validation may reject it but must not crash.

#include <cstddef>
#include <cstdint>
#include <string>

#include <fastdds/rtps/common/SerializedPayload.h>

#include "fuzz_targets.hpp"
#include "framePubSubTypes.h"
#include "motionPubSubTypes.h"
#include "segmentationPubSubTypes.h"
#include "tracksPubSubTypes.h"
#include "uavmot/dds/chain_convert.hpp"
#include "uavmot/dds/frame_convert.hpp"

namespace {

template <class PubSubType>
void check(const uint8_t* data, size_t size) {
  eprosima::fastrtps::rtps::SerializedPayload_t payload(static_cast<uint32_t>(size));
  std::copy(data, data + size, payload.data);
  payload.length = static_cast<uint32_t>(size);
  PubSubType type;
  typename PubSubType::type sample;
  try {
    if (!type.deserialize(&payload, &sample)) return;
  } catch (...) {
    return;  // Fast CDR reports truncated input by exception; the reader drops such a sample
  }
  std::string why;
  (void)uavmot::dds::from_msg(sample, why);
}

}  // namespace

namespace uavmot::fuzz {

int sample_validators(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  switch (data[0] % 4) {
    case 0: check<uavmot::msg::FramePubSubType>(data + 1, size - 1); break;
    case 1: check<uavmot::msg::MotionEstimatePubSubType>(data + 1, size - 1); break;
    case 2: check<uavmot::msg::SegmentationPubSubType>(data + 1, size - 1); break;
    default: check<uavmot::msg::TrackListPubSubType>(data + 1, size - 1); break;
  }
  return 0;
}

}  // namespace uavmot::fuzz
