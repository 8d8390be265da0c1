#pragma once
// A typed sample to and from its serialized CDR form, the encapsulation header included: the
// bytes a Fast DDS 2.9 DataReader receives for uavmot's (XCDR1, final) types, and what an MCAP
// "cdr" message holds. On the wire the serialized sample is followed by zeros up to a multiple
// of 4 bytes (RTPS submessages are 4-byte aligned; Fast DDS leaves the encapsulation options at
// 0), so to_cdr() pads the same way: the recorded bytes equal the received ones (tested).

#include <cstdint>
#include <cstring>
#include <vector>

#include <fastdds/rtps/common/SerializedPayload.h>

#include "uavmot/core/error.hpp"

namespace uavmot::record {

template <class PubSubType>
std::vector<uint8_t> to_cdr(PubSubType& type, typename PubSubType::type& sample) {
  const uint32_t bound = type.getSerializedSizeProvider(&sample)();
  std::vector<uint8_t> bytes(bound + 3u);
  // Serialize straight into the vector: the payload borrows its buffer and gives it back.
  eprosima::fastrtps::rtps::SerializedPayload_t payload;
  payload.data = bytes.data();
  payload.max_size = bound;
  const bool ok = type.serialize(&sample, &payload);
  const uint32_t length = payload.length;
  payload.data = nullptr;
  payload.max_size = 0;
  if (!ok) throw InputError("cannot serialize a " + std::string(type.getName()) + " sample to CDR");
  bytes.resize((length + 3u) & ~3u, 0);  // zero padding to the RTPS alignment, as received
  return bytes;
}

// Throws InputError (naming `what`) when the bytes are not a valid CDR sample of the type.
template <class PubSubType>
void from_cdr(PubSubType& type, const uint8_t* data, size_t size, typename PubSubType::type& sample,
              const std::string& what) {
  if (size < 4) throw InputError(what + ": " + std::to_string(size) + " bytes cannot hold a CDR sample");
  eprosima::fastrtps::rtps::SerializedPayload_t payload(static_cast<uint32_t>(size));
  std::memcpy(payload.data, data, size);
  payload.length = static_cast<uint32_t>(size);
  bool ok = false;
  try {
    ok = type.deserialize(&payload, &sample);
  } catch (const std::exception& e) {
    throw InputError(what + ": not a valid " + type.getName() + " CDR sample (" + e.what() + ")");
  }
  if (!ok) throw InputError(what + ": not a valid " + std::string(type.getName()) + " CDR sample");
}

}  // namespace uavmot::record
