#include "uavmot/geo/chain_ground.hpp"

#include <algorithm>

#include "uavmot/core/error.hpp"

namespace uavmot::geo {

ChainGround::ChainGround(FlightMetadata flight, std::int64_t first_input_frame)
    : flight_(std::move(flight)), offset_(first_input_frame - 1) {
  if (first_input_frame < 1) throw InvalidArgument("ChainGround: the first input frame must be >= 1");
  for (std::size_t i = static_cast<std::size_t>(std::min<std::int64_t>(offset_, static_cast<std::int64_t>(flight_.frames.size())));
       i < flight_.frames.size(); ++i) {
    if (flight_.frames[i] && flight_.frames[i]->has_ground_mapping()) ++mapped_frames_;
  }
}

const FrameGeometry* ChainGround::frame(std::int64_t chain_frame) const {
  const std::int64_t input_frame = chain_frame + offset_;
  if (chain_frame < 1 || input_frame > static_cast<std::int64_t>(flight_.frames.size())) return nullptr;
  const auto& g = flight_.frames[static_cast<std::size_t>(input_frame - 1)];
  return g ? &*g : nullptr;
}

PixelToLatLon ChainGround::pixel_to_lat_lon() const {
  return [this](std::int64_t chain_frame, double x, double y) -> std::optional<std::array<double, 2>> {
    const FrameGeometry* g = frame(chain_frame);
    if (!g) return std::nullopt;
    const auto p = g->pixel_to_lat_lon({x, y});
    if (!p) return std::nullopt;
    return std::array<double, 2>{p->lat_deg, p->lon_deg};
  };
}

MetadataSummary ChainGround::summary() const {
  MetadataSummary s;
  s.packets = static_cast<std::int64_t>(flight_.summary.packets);
  s.standard = metadata_standard(flight_);
  s.bad_checksums = static_cast<std::int64_t>(flight_.summary.bad_checksum);
  s.frames_with_geometry = static_cast<std::int64_t>(flight_.summary.frames_with_geometry);
  return s;
}

std::optional<double> ChainGround::median_gsd_m(std::int64_t frame_count) const {
  std::vector<double> gsds;
  const std::int64_t last = frame_count > 0 ? frame_count : static_cast<std::int64_t>(flight_.frames.size()) - offset_;
  for (std::int64_t k = 1; k <= last; ++k) {
    const FrameGeometry* g = frame(k);
    if (g && g->gsd_m_per_px()) gsds.push_back(*g->gsd_m_per_px());
  }
  if (gsds.empty()) return std::nullopt;
  std::sort(gsds.begin(), gsds.end());
  const std::size_t n = gsds.size();
  return n % 2 == 1 ? gsds[n / 2] : 0.5 * (gsds[n / 2 - 1] + gsds[n / 2]);
}

GeoJsonCounts ChainGround::write_geojson(const std::filesystem::path& path, const TrackMapRecorder& tracks, double fps) const {
  if (offset_ == 0) return tracks.write(path, flight_.frames, fps);
  std::vector<std::optional<FrameGeometry>> shifted;
  for (std::size_t i = static_cast<std::size_t>(std::min<std::int64_t>(offset_, static_cast<std::int64_t>(flight_.frames.size())));
       i < flight_.frames.size(); ++i) {
    shifted.push_back(flight_.frames[i]);
  }
  return tracks.write(path, shifted, fps);
}

}  // namespace uavmot::geo
