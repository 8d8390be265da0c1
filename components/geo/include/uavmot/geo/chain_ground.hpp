#pragma once
// The ground under a chain's frames, for `uavmot process` and the sink: the input's flight
// metadata (read_flight_metadata) with the chain's frame numbering. The chain numbers the frames
// it got from 1 (`--start S` makes input frame S chain frame 1), the metadata numbers the input's.
// Gives the result files their lat,lon columns, summary.json its `metadata` and writes
// tracks.geojson from the confirmed tracks.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "uavmot/core/result_files.hpp"
#include "uavmot/geo/flight_metadata.hpp"
#include "uavmot/geo/track_map.hpp"

namespace uavmot::geo {

class ChainGround {
 public:
  // first_input_frame: the input frame that is chain frame 1 (>= 1).
  explicit ChainGround(FlightMetadata flight, std::int64_t first_input_frame = 1);

  const FlightMetadata& flight() const { return flight_; }
  // True when at least one frame has a pixel <-> ground mapping.
  bool has_ground_mapping() const { return mapped_frames_ > 0; }
  // nullptr for frames without geometry.
  const FrameGeometry* frame(std::int64_t chain_frame) const;
  // For ResultFilesOptions::pixel_to_lat_lon; refers to *this, which must outlive the writer.
  PixelToLatLon pixel_to_lat_lon() const;
  // summary.json's `metadata`.
  MetadataSummary summary() const;
  // The median GSD over the chain's frames that have one (frame_count: the chain's frames; 0 = all
  // the metadata covers).
  std::optional<double> median_gsd_m(std::int64_t frame_count = 0) const;
  // Writes the recorder's tracks as GeoJSON, times from the chain's frame 1.
  GeoJsonCounts write_geojson(const std::filesystem::path& path, const TrackMapRecorder& tracks, double fps) const;

 private:
  FlightMetadata flight_;
  std::int64_t offset_ = 0;  // input frame = chain frame + offset_
  std::int64_t mapped_frames_ = 0;
};

}  // namespace uavmot::geo
