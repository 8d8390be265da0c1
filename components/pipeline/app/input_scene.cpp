#include "input_scene.hpp"

#include <filesystem>

#include <spdlog/spdlog.h>

#include "uavmot/core/yaml_config.hpp"

namespace uavmot::pipeline {

std::optional<geo::ClifPosSequence> read_clif_pos_for(const std::string& input_path) {
  auto seq = geo::read_clif_pos_sequence(input_path);
  if (!seq) return std::nullopt;
  spdlog::info("CLIF POS records in '{}': {} of {} images{}", seq->pos_dir.string(), seq->records.size(), seq->images,
               seq->median_interval_s ? fmt::format(", median GPS time step {:.3f} s ({:.3f} fps)", *seq->median_interval_s, *seq->fps())
                                      : std::string(", too few for a frame rate"));
  return seq;
}

GsdChoice choose_gsd(const GsdCandidates& c) {
  if (c.flag_m > 0.0) {
    spdlog::info("GSD {} m/px from --gsd", c.flag_m);
    return {c.flag_m, "flag"};
  }
  if (c.seqinfo_m > 0.0) {
    spdlog::info("GSD {} m/px from seqinfo.ini", c.seqinfo_m);
    return {c.seqinfo_m, "seqinfo"};
  }
  if (c.klv_m && c.flight) {
    spdlog::info("GSD {:.3f} m/px from KLV metadata ({} packets, {}; median over {} frames)", *c.klv_m, c.flight->summary.packets,
                 geo::metadata_standard(*c.flight), c.flight->summary.frames_with_geometry);
    return {*c.klv_m, "klv"};
  }
  if (c.config_m) {
    spdlog::info("GSD {} m/px from the config (scene.gsd_m)", *c.config_m);
    return {*c.config_m, "config"};
  }
  // Said once: every metric number (sizes, speeds, the tracker's gates in metres) scales with it.
  spdlog::warn("no GSD known (no --gsd, seqinfo.ini gsd, flight metadata{} or config scene.gsd_m): using the default {} m/px; "
               "sizes and speeds in metres scale with it (pass --gsd)",
               c.clif_pos ? "; CLIF POS records hold no focal length, so no GSD" : "", c.default_m);
  return {c.default_m, "default"};
}

std::optional<double> config_gsd_m(const std::string& config_file, double loaded_value) {
  if (config_file.empty()) return std::nullopt;
  const ConfigNode root = ConfigNode::load_file(config_file);
  if (!root.has("scene") || !root.child("scene").has("gsd_m")) return std::nullopt;
  return loaded_value;
}

}  // namespace uavmot::pipeline
