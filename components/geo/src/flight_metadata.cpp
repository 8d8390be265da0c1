#include "uavmot/geo/flight_metadata.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <string>

#include "uavmot/core/error.hpp"

namespace uavmot::geo {

namespace {

std::string lower_extension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

// The first two packets' worth of bytes, enough to tell a transport stream.
bool file_starts_like_mpegts(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::vector<std::uint8_t> head(2 * kTsPacketSize);
  in.read(reinterpret_cast<char*>(head.data()), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(std::max<std::streamsize>(in.gcount(), 0)));
  return looks_like_mpegts(head);
}

std::optional<double> median(std::vector<double> values) {
  if (values.empty()) return std::nullopt;
  const std::size_t mid = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(mid), values.end());
  const double upper = values[mid];
  if (values.size() % 2 == 1) return upper;
  const double lower = *std::max_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(mid));
  return (lower + upper) / 2.0;
}

FlightMetadata empty_flight_metadata(cv::Size image_size, double fps, int frame_count) {
  if (!(fps > 0.0) || !std::isfinite(fps)) throw InvalidArgument("read_flight_metadata: fps must be positive, got " + std::to_string(fps));
  if (image_size.width <= 0 || image_size.height <= 0) throw InvalidArgument("read_flight_metadata: image size must be positive");
  if (frame_count < 0) throw InvalidArgument("read_flight_metadata: frame_count must be >= 0");
  FlightMetadata out;
  out.fps = fps;
  out.image_size = image_size;
  return out;
}

}  // namespace

const FrameGeometry* FlightMetadata::frame(int frame_index) const {
  if (frame_index < 1 || static_cast<std::size_t>(frame_index) > frames.size()) return nullptr;
  const auto& g = frames[static_cast<std::size_t>(frame_index - 1)];
  return g ? &*g : nullptr;
}

FlightMetadata flight_metadata_from_stream(const MpegTsKlv& stream, cv::Size image_size, double fps, int frame_count) {
  FlightMetadata out = empty_flight_metadata(image_size, fps, frame_count);
  out.first_video_pts = stream.first_video_pts;
  out.summary.transport = stream.counts;
  out.summary.klv_units = stream.klv.size();

  std::optional<std::int64_t> last_pts;
  for (const KlvPacket& unit : stream.klv) {
    std::optional<UasMetadata> decoded;
    try {
      decoded = decode_uas_metadata(unit.bytes);
    } catch (const InputError&) {
      ++out.summary.undecodable;
      continue;
    }
    if (!decoded) {
      ++out.summary.other_keys;
      continue;
    }
    const auto pts = unit.pts ? unit.pts : last_pts;
    if (!pts) continue;  // nothing to place it in time by
    last_pts = pts;
    ++out.summary.packets;
    if (decoded->checksum_ok == false) ++out.summary.bad_checksum;
    out.packets.push_back({*pts, std::move(*decoded)});
  }
  if (out.packets.empty()) return out;

  // Frame 1 is the first video frame; without video, the first metadata packet.
  const std::int64_t origin = stream.first_video_pts.value_or(out.packets.front().pts);
  const double ticks_per_frame = kPtsClockHz / fps;
  if (frame_count == 0) {
    std::int64_t last = out.packets.back().pts;
    for (const auto& p : out.packets) last = std::max(last, p.pts);
    for (const std::int64_t p : stream.video_pes_pts) last = std::max(last, p);
    const double frames = last < origin ? 0.0 : std::floor(static_cast<double>(last - origin) / ticks_per_frame + 1e-6) + 1.0;
    // Damaged PTS can span hours: cap what a stream alone can make us allocate.
    frame_count = static_cast<int>(std::min(frames, static_cast<double>(kMaxAutomaticFrames)));
  }

  // Packets by time (stable: same-PTS packets keep stream order, the later one wins).
  std::vector<std::size_t> order(out.packets.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return out.packets[a].pts < out.packets[b].pts; });

  out.frames.resize(static_cast<std::size_t>(frame_count));
  std::vector<double> gsds;
  std::size_t next = 0;
  std::optional<std::size_t> current;
  std::optional<std::size_t> geometry_of;  // the packet current_geometry was made from
  std::optional<FrameGeometry> current_geometry;
  for (int k = 1; k <= frame_count; ++k) {
    const double frame_pts = static_cast<double>(origin) + (k - 1) * ticks_per_frame;
    while (next < order.size() && static_cast<double>(out.packets[order[next]].pts) <= frame_pts + 1e-6) current = order[next++];
    if (!current) continue;
    if (geometry_of != current) {
      current_geometry = FrameGeometry::from_metadata(out.packets[*current].metadata, image_size);
      geometry_of = current;
    }
    out.frames[static_cast<std::size_t>(k - 1)] = current_geometry;
    ++out.summary.frames_with_geometry;
    if (current_geometry->gsd_m_per_px()) gsds.push_back(*current_geometry->gsd_m_per_px());
  }
  out.summary.median_gsd_m_per_px = median(std::move(gsds));
  return out;
}

std::string metadata_standard(const FlightMetadata& flight) {
  bool st0601 = false, eg0104 = false;
  for (const TimedMetadata& p : flight.packets) {
    (p.metadata.standard == MetadataStandard::kEg0104 ? eg0104 : st0601) = true;
  }
  if (st0601 && eg0104) return "ST 0601 + EG 0104";
  return st0601 ? "ST 0601" : eg0104 ? "EG 0104" : "";
}

FlightMetadata read_flight_metadata(const std::filesystem::path& path, cv::Size image_size, double fps, int frame_count) {
  const std::string ext = lower_extension(path);
  const bool ts_extension = ext == ".ts" || ext == ".m2t" || ext == ".mpg" || ext == ".mpeg";
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    if (ts_extension) throw InputError(path.string() + ": no such file");
    return empty_flight_metadata(image_size, fps, frame_count);  // a folder of frames: no KLV
  }
  if (ext != ".ts" && !file_starts_like_mpegts(path)) {
    return empty_flight_metadata(image_size, fps, frame_count);  // images, MP4, program streams: no KLV
  }
  return flight_metadata_from_stream(read_mpegts_klv(path), image_size, fps, frame_count);
}

}  // namespace uavmot::geo
