#pragma once
// What `uavmot process` learns about the scene from its input besides the frames (docs/geo.md):
// the frame rate of a CLIF-style image folder from its POS records, the flight metadata of an
// MPEG-TS (ground geometry per frame, GSD), and which GSD the chain uses, said once in the log.

#include <optional>
#include <string>

#include "uavmot/geo/clif_pos_sequence.hpp"
#include "uavmot/geo/flight_metadata.hpp"

namespace uavmot::pipeline {

// A CLIF-style folder's POS records (INPUT/../pos), or nullopt for other inputs. Logs what it found.
std::optional<geo::ClifPosSequence> read_clif_pos_for(const std::string& input_path);

// The GSD candidates, most trusted first: --gsd, seqinfo.ini, the flight metadata's median
// per-frame GSD, the config's scene.gsd_m, else the default.
struct GsdCandidates {
  double flag_m = 0.0;     // 0 = not given
  double seqinfo_m = 0.0;  // 0 = not given
  const geo::FlightMetadata* flight = nullptr;
  std::optional<double> klv_m;    // the median over the chain's frames
  std::optional<double> config_m;  // only when the config file sets scene.gsd_m
  double default_m = 0.35;
  bool clif_pos = false;  // the input has POS records (which cannot give a GSD)
};

struct GsdChoice {
  double gsd_m = 0.0;
  std::string source;  // flag, seqinfo, klv, config, default (summary.json gsd_source)
};

// Picks the GSD and logs one line naming its source ("GSD 0.048 m/px from KLV metadata (48
// packets, EG 0104)"); without any, one warning naming the default.
GsdChoice choose_gsd(const GsdCandidates& c);

// Whether the config file sets scene.gsd_m, and to what.
std::optional<double> config_gsd_m(const std::string& config_file, double loaded_value);

}  // namespace uavmot::pipeline
