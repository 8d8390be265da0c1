#pragma once
// The one CDR encoder: the payload of an MCAP "cdr" message, which is also what a Fast DDS 2.9
// reader receives for uavmot's (XCDR1, final) types: the 4-byte encapsulation header, the fields
// as `write_fields` serializes them with Fast CDR, then zeros up to a multiple of 4 bytes (RTPS
// submessages are 4-byte aligned). Used for uavmot's generated types (record) and for the
// Foxglove schema messages (components/foxglove), so both encode the same way.

#include <cstdint>
#include <string>
#include <vector>

#include <fastcdr/Cdr.h>
#include <fastcdr/FastBuffer.h>
#include <fastcdr/exceptions/Exception.h>

#include "uavmot/core/error.hpp"

namespace uavmot::mcap {

// `max_size`: an upper bound of the encoded size, encapsulation header included. Throws
// InputError naming `what` when the fields do not fit (a wrong bound) or cannot be encoded.
template <class WriteFields>
std::vector<uint8_t> encode_cdr(size_t max_size, const std::string& what, WriteFields&& write_fields) {
  std::vector<uint8_t> bytes(max_size + 3u);
  // Serialize straight into the vector: no copy of large payloads (frames).
  eprosima::fastcdr::FastBuffer buffer(reinterpret_cast<char*>(bytes.data()), max_size);
  eprosima::fastcdr::Cdr cdr(buffer, eprosima::fastcdr::Cdr::DEFAULT_ENDIAN, eprosima::fastcdr::Cdr::DDS_CDR);
  try {
    cdr.serialize_encapsulation();
    write_fields(cdr);
  } catch (const eprosima::fastcdr::exception::Exception& e) {
    throw InputError("cannot encode a " + what + " as CDR (" + e.what() + ")");
  }
  bytes.resize((cdr.getSerializedDataLength() + 3u) & ~size_t{3});  // zero padding, as received
  return bytes;
}

}  // namespace uavmot::mcap
