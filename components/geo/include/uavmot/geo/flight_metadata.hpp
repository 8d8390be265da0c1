#pragma once
// Per-frame ground geometry of a whole video: read_flight_metadata() reads the KLV of an MPEG-TS
// file, decodes every ST 0601 / EG 0104 packet, and gives frame k the geometry of the latest
// packet at or before frame k's presentation time, where frame k (1-based) is shown at
//   first video PTS + (k - 1) * 90000 / fps.
// `fps` must be the rate of decoded frames (aphill_short.ts: 29.97; its video PES are fields,
// and ffprobe's r_frame_rate says 59.94). Packets without a PTS take the previous packet's.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core/types.hpp>

#include "uavmot/geo/frame_geometry.hpp"
#include "uavmot/geo/mpegts_klv.hpp"
#include "uavmot/geo/uas_metadata.hpp"

namespace uavmot::geo {

// The most frames frame_count = 0 derives from a stream's PTS (about 1.9 h at 29.97 fps), so a
// damaged PTS cannot make the reader allocate for days of video; pass frame_count for longer ones.
inline constexpr int kMaxAutomaticFrames = 200000;

struct TimedMetadata {
  std::int64_t pts = 0;  // 90 kHz, unwrapped
  UasMetadata metadata;
};

struct FlightMetadataSummary {
  std::size_t klv_units = 0;         // KLV units found in the metadata streams
  std::size_t packets = 0;           // decoded ST 0601 / EG 0104 packets
  std::size_t bad_checksum = 0;      // ST 0601 packets whose checksum does not match (still used)
  std::size_t undecodable = 0;       // ST 0601 / EG 0104 units whose structure is broken (skipped)
  std::size_t other_keys = 0;        // KLV units of other sets (ignored)
  std::size_t frames_with_geometry = 0;
  std::optional<double> median_gsd_m_per_px;  // over frames with a GSD
  MpegTsCounts transport;            // what the transport stream reader skipped
};

struct FlightMetadata {
  double fps = 0.0;
  cv::Size image_size;
  std::optional<std::int64_t> first_video_pts;
  std::vector<TimedMetadata> packets;               // decoded, in stream order
  std::vector<std::optional<FrameGeometry>> frames;  // frames[k - 1] is frame k
  FlightMetadataSummary summary;

  bool empty() const { return packets.empty(); }
  // nullptr when frame is out of range or no packet came at or before it.
  const FrameGeometry* frame(int frame_index) const;
};

// For an MPEG transport stream (extension .ts/.m2t/.mpg/.mpeg that starts with TS sync bytes, or
// any file that does): the per-frame geometry for frames 1..frame_count (frame_count = 0: up to
// the last video or metadata PTS, at most kMaxAutomaticFrames). Any other input gives an empty
// result, not an error. Throws InputError when the file cannot be read or a .ts holds no transport stream, and
// InvalidArgument when fps or the image size is not positive.
FlightMetadata read_flight_metadata(const std::filesystem::path& path, cv::Size image_size, double fps, int frame_count = 0);

// The metadata sets the packets came in: "EG 0104", "ST 0601", "ST 0601 + EG 0104", or "" without
// packets (for logs and summary.json).
std::string metadata_standard(const FlightMetadata& flight);

// The same from an already parsed stream (tests, callers with the bytes in memory).
FlightMetadata flight_metadata_from_stream(const MpegTsKlv& stream, cv::Size image_size, double fps, int frame_count = 0);

}  // namespace uavmot::geo
