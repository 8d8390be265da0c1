#pragma once
// KLV metadata out of an MPEG-2 transport stream (ISO/IEC 13818-1, MISB ST 1402): 188-byte packets,
// PAT -> PMT -> the metadata elementary stream (stream_type 0x15, metadata in PES, or 0x06 private
// data, which is how most STANAG 4609 files carry KLV), PES reassembly, and each KLV unit with the
// PTS of its PES. Also the PTS of every video PES, so metadata can be put on video frames.
// Tolerant: bytes out of sync are skipped until two sync bytes 188 apart, broken packets and PES
// are skipped and counted; only input with no transport stream in it at all is an InputError.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "uavmot/geo/klv.hpp"

namespace uavmot::geo {

inline constexpr std::size_t kTsPacketSize = 188;
inline constexpr double kPtsClockHz = 90000.0;

struct KlvPacket {
  std::vector<std::uint8_t> bytes;  // key, BER length and value of one KLV unit
  // PTS of the PES that carried it (90 kHz), unwrapped past the 33-bit roll-over so it only grows
  // with the stream; nullopt when that PES had none (asynchronous metadata).
  std::optional<std::int64_t> pts;
  std::uint16_t pid = 0;
};

// What was skipped, so a caller can report damage without failing.
struct MpegTsCounts {
  std::size_t ts_packets = 0;           // whole 188-byte packets read
  std::size_t resync_bytes = 0;         // bytes skipped to find sync again
  std::size_t bad_packets = 0;          // transport error flag, or an adaptation field longer than the packet
  std::size_t bad_sections = 0;         // PAT/PMT sections that do not parse
  std::size_t bad_pes = 0;              // PES without a start code or with a header past its end
  std::size_t truncated_pes = 0;        // PES shorter than its PES_packet_length (cut or lost packets)
  std::size_t truncated_klv = 0;        // KLV units whose length runs past their PES
  std::size_t non_klv_bytes = 0;        // metadata payload bytes outside any KLV unit (e.g. AU cell headers)
};

struct MpegTsKlv {
  std::vector<KlvPacket> klv;               // in stream order
  std::vector<std::int64_t> video_pes_pts;  // PTS of each video PES, in stream (decode) order
  // The smallest video PTS: frame 1's presentation time. A video PES can hold one field of an
  // interlaced frame (aphill_short.ts: 96 PES, 48 frames), so the list is not a frame list.
  std::optional<std::int64_t> first_video_pts;
  std::vector<std::uint16_t> metadata_pids;
  std::optional<std::uint16_t> video_pid;
  MpegTsCounts counts;
};

// `name` labels error messages (a file name). Throws InputError when no two sync bytes 188 apart
// are found anywhere (not a transport stream).
MpegTsKlv parse_mpegts_klv(Bytes data, const std::string& name = "MPEG-TS input");
// Reads the whole file; InputError when it cannot be read or holds no transport stream.
MpegTsKlv read_mpegts_klv(const std::filesystem::path& path);

// True when `data` starts like a transport stream (sync bytes at 0 and 188, or at 0 for a
// single-packet input).
bool looks_like_mpegts(Bytes data);

}  // namespace uavmot::geo
