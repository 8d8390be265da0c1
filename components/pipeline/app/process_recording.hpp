#pragma once
// `uavmot process REC.mcap`: re-runs tracking on the motion estimates and segmentation results
// of a recording (e.g. with new tracking parameters, on the ground) and writes the result files.

#include <string>

#include "uavmot/pipeline/chain.hpp"

namespace uavmot::pipeline {

// Writes tracks.txt ... to `out_dir` (one sub-folder per stream when the recording holds several).
// Returns the exit code: damage in the recording is reported and gives kExitBadInput after
// everything before it was processed.
int process_recording(const std::string& recording, const std::string& out_dir, ChainOptions options);

}  // namespace uavmot::pipeline
