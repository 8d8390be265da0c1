#pragma once
// uavmot::Frame <-> uavmot::msg::Frame. Raw encodings are copied bit for bit; received samples
// are validated before use (size against width x height x channels).

#include <optional>
#include <string>

#include "frame.h"
#include "uavmot/core/chain_types.hpp"

namespace uavmot::dds {

msg::Frame to_msg(const Frame& frame);
// The frame as a JPEG (encoding JPEG, width/height of the image), e.g. for a preview.
msg::Frame to_jpeg_msg(const Frame& frame, int quality);
// The end-of-stream marker: no pixels, end_of_stream = true.
msg::Frame end_of_stream_frame(const std::string& stream_id, int64_t last_index);

// Returns the frame, or nullopt with `why` set when the sample is malformed.
std::optional<Frame> from_msg(const msg::Frame& sample, std::string& why);
// The same without copying raw pixels: the image refers to sample.data(), so it is valid only
// while the sample is neither changed nor destroyed (a node that processes the frame at once).
std::optional<Frame> view_msg(msg::Frame& sample, std::string& why);

int channels_of(msg::Encoding encoding);  // 1, 3, or 0 for compressed

}  // namespace uavmot::dds
