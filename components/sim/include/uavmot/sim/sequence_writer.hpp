#pragma once
// Writes a simulated sequence as an MOTChallenge folder (docs/sim.md):
//   seqinfo.ini, img1/000001.jpg..., gt/gt.txt (moving), gt/all_objects.txt, gt/gt_obb.csv,
//   gt/homographies.txt, gt/masks/000001.png (16-bit ids), meta.json, video.mp4.

#include <cstdint>
#include <functional>
#include <string>

#include "uavmot/sim/scenario.hpp"

namespace uavmot::sim {

struct WriteSummary {
  int frames = 0;
  int vehicles = 0;
  int moving_vehicles = 0;
  int parked_vehicles = 0;
  int64_t moving_instances = 0;  // lines of gt.txt
};

// Called after each frame with (frames written, total frames).
using ProgressCallback = std::function<void(int, int)>;

// Throws InputError when `out_dir` cannot be created or written.
WriteSummary write_sequence(const Scenario& scenario, uint64_t seed, const std::string& out_dir,
                            const ProgressCallback& progress = {});

}  // namespace uavmot::sim
