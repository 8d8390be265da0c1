#pragma once
// The one CDR helper for uavmot's generated types: a typed sample to and from its serialized CDR
// form, the encapsulation header included: the bytes a Fast DDS 2.9 DataReader receives for
// uavmot's (XCDR1, final) types, what an MCAP "cdr" message holds (record, replay) and what the
// tracking node's state file holds. to_cdr() encodes with mcap::encode_cdr (zero padding to 4
// bytes as on the wire), the encoder the Foxglove schema messages use too: the recorded bytes
// equal the received ones (record_tests).

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include <fastdds/rtps/common/SerializedPayload.h>

#include "uavmot/core/error.hpp"
#include "uavmot/mcap/cdr.hpp"

namespace uavmot::dds {

template <class PubSubType>
std::vector<uint8_t> to_cdr(PubSubType& type, typename PubSubType::type& sample) {
  // The bound the type itself gives Fast DDS (header included), then the one CDR encoder.
  const uint32_t bound = type.getSerializedSizeProvider(&sample)();
  return mcap::encode_cdr(bound, std::string(type.getName()) + " sample",
                          [&](eprosima::fastcdr::Cdr& cdr) { sample.serialize(cdr); });
}

template <class PubSubType>
std::vector<uint8_t> to_cdr(typename PubSubType::type& sample) {
  PubSubType type;
  return to_cdr(type, sample);
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

}  // namespace uavmot::dds
