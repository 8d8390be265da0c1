#pragma once
// Stream ids arrive from the wire (DDS samples, recordings) and name folders and files
// (out/<stream>/, previews/<stream>_<frame>.jpg): only ids that are safe as one path component
// are accepted: 1 to 64 of [A-Za-z0-9._-], not "." or "..".

#include <string>
#include <string_view>

namespace uavmot {

inline constexpr size_t kMaxStreamIdLength = 64;

// Why ID cannot be a stream id, or empty when it can.
std::string stream_id_problem(std::string_view id);
inline bool is_valid_stream_id(std::string_view id) { return stream_id_problem(id).empty(); }

// ID for a log line: quoted, non-printable bytes as \xNN, cut after 80 characters.
std::string printable_stream_id(std::string_view id);

}  // namespace uavmot
