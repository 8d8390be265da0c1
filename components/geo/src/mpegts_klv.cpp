#include "uavmot/geo/mpegts_klv.hpp"

#include <algorithm>
#include <fstream>
#include <iterator>
#include <map>
#include <set>

#include "uavmot/core/error.hpp"

namespace uavmot::geo {

namespace {

constexpr std::uint8_t kSyncByte = 0x47;
constexpr std::uint16_t kPatPid = 0x0000;
constexpr std::uint16_t kLastReservedPid = 0x001F;  // PAT, CAT, and the DVB/ATSC SI tables
constexpr std::uint16_t kNullPid = 0x1FFF;
constexpr std::size_t kMaxSectionSize = 3 + 1021;       // PAT/PMT section_length is at most 1021
constexpr std::size_t kMaxPesSize = 16u * 1024u * 1024u;  // a metadata PES is a few kB; caps garbage
constexpr std::int64_t kPtsModulus = std::int64_t{1} << 33;

enum class StreamKind { kMetadata, kVideo, kOther };

bool is_video_stream_type(std::uint8_t type) {
  switch (type) {
    case 0x01: case 0x02: case 0x10: case 0x1B: case 0x24: case 0x33: case 0x42:
      return true;
    default:
      return false;
  }
}

// DVB descriptors that mark a private-data (0x06) stream as audio or subtitles, not metadata.
bool is_dvb_media_descriptor(std::uint8_t tag) { return tag == 0x56 || tag == 0x59 || tag == 0x6A || tag == 0x7A || tag == 0x7B; }

// Stream ids whose PES has no optional header (13818-1 table 2-21).
bool pes_has_no_optional_header(std::uint8_t stream_id) {
  return stream_id == 0xBC || stream_id == 0xBE || stream_id == 0xBF || stream_id == 0xF0 || stream_id == 0xF1 ||
         stream_id == 0xF2 || stream_id == 0xF8 || stream_id == 0xFF;
}

std::uint64_t read_pts_field(Bytes b) {
  return (static_cast<std::uint64_t>(b[0] & 0x0E) << 29) | (static_cast<std::uint64_t>(b[1]) << 22) |
         (static_cast<std::uint64_t>(b[2] & 0xFE) << 14) | (static_cast<std::uint64_t>(b[3]) << 7) |
         (static_cast<std::uint64_t>(b[4]) >> 1);
}

// PTS are 33-bit and roll over every 26.5 h; a jump back by more than half the range is a wrap.
// Decode-order PTS go back a little (B-frames), which stays far from that threshold.
class PtsUnwrapper {
 public:
  std::int64_t operator()(std::uint64_t raw) {
    std::int64_t value = static_cast<std::int64_t>(raw) + offset_;
    if (last_ && value < *last_ - kPtsModulus / 2) {
      offset_ += kPtsModulus;
      value += kPtsModulus;
    }
    last_ = value;
    return value;
  }

 private:
  std::optional<std::int64_t> last_;
  std::int64_t offset_ = 0;
};

struct PesHeader {
  std::uint8_t stream_id = 0;
  std::size_t declared_size = 0;  // 6 + PES_packet_length, 0 when unbounded (allowed for video)
  std::size_t payload_offset = 0;
  std::optional<std::uint64_t> pts;
};

std::optional<PesHeader> parse_pes_header(Bytes pes) {
  if (pes.size() < 6 || pes[0] != 0x00 || pes[1] != 0x00 || pes[2] != 0x01) return std::nullopt;
  PesHeader header;
  header.stream_id = pes[3];
  const std::size_t length = (static_cast<std::size_t>(pes[4]) << 8) | pes[5];
  header.declared_size = length == 0 ? 0 : 6 + length;
  if (pes_has_no_optional_header(header.stream_id)) {
    header.payload_offset = 6;
    return header;
  }
  if (pes.size() < 9) return std::nullopt;
  const std::size_t header_data_length = pes[8];
  if (9 + header_data_length > pes.size()) return std::nullopt;
  header.payload_offset = 9 + header_data_length;
  const bool has_pts = (pes[7] & 0x80) != 0;
  if (has_pts && header_data_length >= 5) header.pts = read_pts_field(pes.subspan(9, 5));
  return header;
}

struct Buffer {
  std::vector<std::uint8_t> bytes;
  bool active = false;
};

class TransportStreamParser {
 public:
  explicit TransportStreamParser(MpegTsKlv& out) : out_(out) {}

  void packet(Bytes pkt) {
    ++out_.counts.ts_packets;
    const bool transport_error = (pkt[1] & 0x80) != 0;
    const bool unit_start = (pkt[1] & 0x40) != 0;
    const auto pid = static_cast<std::uint16_t>(((pkt[1] & 0x1F) << 8) | pkt[2]);
    const int adaptation = (pkt[3] >> 4) & 0x3;
    if (transport_error) {
      ++out_.counts.bad_packets;
      drop_pes(pid);  // the PES it belonged to has a hole now
      return;
    }
    std::size_t offset = 4;
    if (adaptation & 0x2) {
      offset = 5 + static_cast<std::size_t>(pkt[4]);
      if (offset > kTsPacketSize) {
        ++out_.counts.bad_packets;
        return;
      }
    }
    if ((adaptation & 0x1) == 0 || pid == kNullPid) return;
    const Bytes payload = pkt.subspan(offset);
    if (pid == kPatPid || pmt_pids_.count(pid) != 0) {
      section(pid, unit_start, payload);
    } else if (pid > kLastReservedPid) {
      pes(pid, unit_start, payload);
    }
  }

  void finish() {
    for (auto& [pid, buffer] : pes_) {
      if (buffer.active) flush_pes(pid, buffer);
    }
    for (const auto& [pid, kind] : kinds_) {
      if (kind == StreamKind::kMetadata) out_.metadata_pids.push_back(pid);
    }
  }

 private:
  void section(std::uint16_t pid, bool unit_start, Bytes payload) {
    Buffer& buffer = sections_[pid];
    if (unit_start) {
      const std::size_t pointer = payload.empty() ? payload.size() : payload[0];
      if (payload.empty() || 1 + pointer > payload.size()) {
        ++out_.counts.bad_sections;
        buffer.active = false;
        return;
      }
      const Bytes start = payload.subspan(1 + pointer);
      buffer.bytes.assign(start.begin(), start.end());
      buffer.active = true;
    } else if (buffer.active) {
      buffer.bytes.insert(buffer.bytes.end(), payload.begin(), payload.end());
    } else {
      return;
    }
    if (buffer.bytes.size() < 3) return;
    const std::size_t size = 3 + ((static_cast<std::size_t>(buffer.bytes[1] & 0x0F) << 8) | buffer.bytes[2]);
    if (size > kMaxSectionSize) {
      ++out_.counts.bad_sections;
      buffer.active = false;
      return;
    }
    if (buffer.bytes.size() < size) return;
    const Bytes table(buffer.bytes.data(), size);
    const bool parsed = pid == kPatPid ? parse_pat(table) : parse_pmt(table);
    if (!parsed) ++out_.counts.bad_sections;
    buffer.active = false;
  }

  // PAT: program_number (16) and PMT PID (13) pairs after the 8-byte header, CRC-32 last.
  bool parse_pat(Bytes t) {
    if (t[0] != 0x00 || t.size() < 12) return false;
    for (std::size_t i = 8; i + 4 <= t.size() - 4; i += 4) {
      const int program = (t[i] << 8) | t[i + 1];
      const auto pid = static_cast<std::uint16_t>(((t[i + 2] & 0x1F) << 8) | t[i + 3]);
      if (program != 0 && pid > kLastReservedPid && pid != kNullPid) pmt_pids_.insert(pid);
    }
    return true;
  }

  // PMT: program info descriptors, then stream_type (8), PID (13), ES info descriptors per stream.
  bool parse_pmt(Bytes t) {
    if (t[0] != 0x02 || t.size() < 16) return false;
    const std::size_t end = t.size() - 4;  // CRC-32
    std::size_t i = 12 + ((static_cast<std::size_t>(t[10] & 0x0F) << 8) | t[11]);
    while (i + 5 <= end) {
      const std::uint8_t type = t[i];
      const auto pid = static_cast<std::uint16_t>(((t[i + 1] & 0x1F) << 8) | t[i + 2]);
      const std::size_t info_length = (static_cast<std::size_t>(t[i + 3] & 0x0F) << 8) | t[i + 4];
      const std::size_t info_end = std::min(end, i + 5 + info_length);
      bool media_descriptor = false;
      for (std::size_t d = i + 5; d + 2 <= info_end; d += 2 + t[d + 1]) media_descriptor |= is_dvb_media_descriptor(t[d]);
      if (type == 0x15 || (type == 0x06 && !media_descriptor)) {
        kinds_[pid] = StreamKind::kMetadata;
      } else if (is_video_stream_type(type)) {
        kinds_[pid] = StreamKind::kVideo;
        if (!out_.video_pid) out_.video_pid = pid;
      } else {
        kinds_[pid] = StreamKind::kOther;
      }
      i += 5 + info_length;
    }
    return true;
  }

  // Streams no PMT described (yet) are classified by the stream_id of their first PES.
  StreamKind kind_of(std::uint16_t pid, Bytes payload) {
    if (const auto it = kinds_.find(pid); it != kinds_.end()) return it->second;
    if (payload.size() < 4 || payload[0] != 0 || payload[1] != 0 || payload[2] != 1) return StreamKind::kOther;
    const std::uint8_t id = payload[3];
    StreamKind kind = StreamKind::kOther;
    if (id >= 0xE0 && id <= 0xEF) {
      kind = StreamKind::kVideo;
      if (!out_.video_pid) out_.video_pid = pid;
    } else if (id == 0xBD || id == 0xFC) {
      kind = StreamKind::kMetadata;
    }
    kinds_[pid] = kind;
    return kind;
  }

  void pes(std::uint16_t pid, bool unit_start, Bytes payload) {
    if (!unit_start && kinds_.count(pid) == 0) return;  // joined mid-PES: wait for a start
    const StreamKind kind = unit_start ? kind_of(pid, payload) : kinds_[pid];
    if (kind == StreamKind::kVideo) {
      if (unit_start) video_pes_start(payload);
      return;
    }
    if (kind != StreamKind::kMetadata) return;
    Buffer& buffer = pes_[pid];
    if (unit_start) {
      if (buffer.active) flush_pes(pid, buffer);
      buffer.bytes.assign(payload.begin(), payload.end());
      buffer.active = true;
    } else if (buffer.active) {
      if (buffer.bytes.size() + payload.size() > kMaxPesSize) {
        ++out_.counts.bad_pes;
        buffer = Buffer{};
        return;
      }
      buffer.bytes.insert(buffer.bytes.end(), payload.begin(), payload.end());
    } else {
      return;
    }
    // A bounded PES is done once its declared length is in: emit it without waiting for the next.
    if (buffer.bytes.size() >= 6) {
      const std::size_t declared = buffer.bytes[4] << 8 | buffer.bytes[5];
      if (declared != 0 && buffer.bytes.size() >= 6 + declared) flush_pes(pid, buffer);
    }
  }

  void video_pes_start(Bytes payload) {
    const auto header = parse_pes_header(payload);
    if (!header) {
      ++out_.counts.bad_pes;
      return;
    }
    if (!header->pts) return;
    const std::int64_t pts = unwrap_(*header->pts);
    out_.video_pes_pts.push_back(pts);
    out_.first_video_pts = out_.first_video_pts ? std::min(*out_.first_video_pts, pts) : pts;
  }

  void drop_pes(std::uint16_t pid) {
    if (const auto it = pes_.find(pid); it != pes_.end() && it->second.active) {
      ++out_.counts.bad_pes;
      it->second = Buffer{};
    }
  }

  void flush_pes(std::uint16_t pid, Buffer& buffer) {
    const Bytes pes(buffer.bytes);
    const auto header = parse_pes_header(pes);
    if (!header) {
      ++out_.counts.bad_pes;
      buffer = Buffer{};
      return;
    }
    std::size_t end = pes.size();
    if (header->declared_size != 0) {
      if (pes.size() < header->declared_size) ++out_.counts.truncated_pes;
      end = std::min(end, header->declared_size);
    }
    const std::optional<std::int64_t> pts = header->pts ? std::optional(unwrap_(*header->pts)) : std::nullopt;
    const Bytes payload = header->payload_offset <= end ? pes.subspan(header->payload_offset, end - header->payload_offset) : Bytes{};
    const KlvSplit split = split_klv_units(payload);
    out_.counts.truncated_klv += split.truncated_units;
    out_.counts.non_klv_bytes += split.skipped_bytes;
    for (const KlvUnit& unit : split.units) {
      const Bytes bytes = payload.subspan(unit.offset, unit.size);
      out_.klv.push_back({std::vector<std::uint8_t>(bytes.begin(), bytes.end()), pts, pid});
    }
    buffer = Buffer{};
  }

  MpegTsKlv& out_;
  std::set<std::uint16_t> pmt_pids_;
  std::map<std::uint16_t, StreamKind> kinds_;
  std::map<std::uint16_t, Buffer> sections_;
  std::map<std::uint16_t, Buffer> pes_;
  PtsUnwrapper unwrap_;
};

bool synced_at(Bytes data, std::size_t pos) {
  return data[pos] == kSyncByte && (pos + kTsPacketSize >= data.size() || data[pos + kTsPacketSize] == kSyncByte);
}

}  // namespace

bool looks_like_mpegts(Bytes data) {
  if (data.size() < kTsPacketSize) return false;
  return data[0] == kSyncByte && (data.size() < 2 * kTsPacketSize || data[kTsPacketSize] == kSyncByte);
}

MpegTsKlv parse_mpegts_klv(Bytes data, const std::string& name) {
  MpegTsKlv out;
  TransportStreamParser parser(out);
  std::size_t pos = 0;
  while (pos + kTsPacketSize <= data.size()) {
    if (synced_at(data, pos)) {
      parser.packet(data.subspan(pos, kTsPacketSize));
      pos += kTsPacketSize;
      continue;
    }
    std::size_t next = pos + 1;
    while (next + kTsPacketSize <= data.size() && !synced_at(data, next)) ++next;
    out.counts.resync_bytes += next - pos;
    pos = next;
  }
  out.counts.resync_bytes += data.size() - pos;  // a cut last packet
  if (out.counts.ts_packets == 0) {
    throw InputError(name + ": not an MPEG transport stream (no 188-byte packets with sync byte 0x47 in " +
                     std::to_string(data.size()) + " bytes)");
  }
  parser.finish();
  return out;
}

MpegTsKlv read_mpegts_klv(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string() + ": cannot open");
  const std::vector<std::uint8_t> data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw InputError(path.string() + ": read error");
  return parse_mpegts_klv(data, path.string());
}

}  // namespace uavmot::geo
