#pragma once
// Paper Tables I and II for the segmentation methods on a simulated sequence: the simulator
// renders frames with ground truth, the motion layer finds the moving features, every method
// segments the same frames, uavmot::eval scores the regions (docs/eval.md has the rules).

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "uavmot/core/chain_types.hpp"
#include "uavmot/eval/evaluate.hpp"
#include "uavmot/segmentation/segmentation_options.hpp"

namespace uavmot::segmentation {

struct SimTablesRequest {
  std::string preset = "paper";
  uint64_t seed = 1;
  int frames = 0;  // 0 = the preset's length
  std::vector<SegmentationMethod> methods{kSegmentationMethods.begin(), kSegmentationMethods.end()};
  SegmentationOptions base;  // `method` is replaced by each of `methods`
  // false: the chain's motion layer finds the moving features (what `uavmot process` does).
  // true: ideal features from the ground truth instead: Shi-Tomasi corners (min distance 3 px)
  // that lie on a moving vehicle, with its true velocity. Several per car, as in the paper
  // (297 moving features in its Fig. 2), which is what makes plain clustering under-segment.
  bool truth_features = false;
};

struct SimTables {
  std::string preset;
  uint64_t seed = 0;
  int frames = 0;
  bool truth_features = false;
  double gsd_m = 0.0;
  // What the motion layer left to find: moving objects (visibility >= 0.5) per frame, and those
  // with at least one feature classified moving on them (box grown by 1 px). Segmentation starts
  // from moving features, so the second over the first bounds every method's correct rate.
  int64_t moving_instances = 0;
  int64_t instances_with_moving_feature = 0;
  std::map<SegmentationMethod, eval::EvaluationResult> results;
};

SimTables run_sim_tables(const SimTablesRequest& request);

// Markdown: Table I (correct / US / OS / miss in %) and Table II (mean errors in px and m).
std::string format_tables(const SimTables& tables);

}  // namespace uavmot::segmentation
