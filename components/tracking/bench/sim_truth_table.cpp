// Tracker accuracy on every simulator preset, fed from the simulator's ground truth with noisy,
// missed and merged regions (tests/sim_truth.hpp). Prints a Markdown table.
//
//   build/bench/tracking_sim_truth_table [--frames N] [--seed S] [--poor]

#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "sim_truth.hpp"

using namespace uavmot;
using namespace uavmot::tracking::testing;

int main(int argc, char** argv) {
  int frames = 250;
  uint64_t seed = 42;
  TruthMeasurementOptions m;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--frames") == 0 && i + 1 < argc) frames = std::atoi(argv[++i]);
    else if (std::strcmp(argv[i], "--seed") == 0 && i + 1 < argc) seed = std::strtoull(argv[++i], nullptr, 10);
    else if (std::strcmp(argv[i], "--poor") == 0) {
      m.region_position_noise_px = 1.2;
      m.region_size_noise_px = 1.5;
      m.region_miss_probability = 0.2;
      m.merge_gap_px = 3.0;
    } else {
      std::fprintf(stderr, "usage: tracking_sim_truth_table [--frames N] [--seed S] [--poor]\n");
      return 2;
    }
  }
  std::printf("| preset | instances | correct | under | over | missed | e_pos px | e_w px | e_l px | id switches / vehicles | parked track-frames | false track-frames |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const auto& preset : sim::preset_names()) {
    if (preset == "hd") continue;  // 1920x1080: same traffic, 4x the rendering time
    const PaperScore s = run_sim_truth(preset, frames, seed, m);
    std::printf("| %s | %d | %.1f %% | %.1f %% | %.1f %% | %.1f %% | %.2f | %.2f | %.2f | %d / %d | %d | %d |\n", preset.c_str(), s.instances,
                100 * s.rate(s.correct), 100 * s.rate(s.under), 100 * s.rate(s.over), 100 * s.rate(s.missed), s.position_error,
                s.width_error, s.length_error, s.id_switches, s.moving_vehicles_tracked, s.parked_track_frames, s.false_track_frames);
  }
  return 0;
}
