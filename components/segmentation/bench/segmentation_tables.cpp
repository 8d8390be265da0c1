// Paper Tables I and II for clustering, korn, morphological, lbp and fusion on simulated
// sequences (docs/segmentation.md keeps the output):
//
//   build/bin/uavmot-segmentation-tables --preset paper --preset dense --seed 1 [--truth-features]

#include <cstdio>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <opencv2/core.hpp>

#include "sim_tables.hpp"
#include "uavmot/core/app.hpp"
#include "uavmot/segmentation/segmentation_options.hpp"

int main(int argc, char** argv) {
  std::vector<std::string> presets;
  uint64_t seed = 1;
  int frames = 0;
  std::string config;
  bool truth_features = false;
  return uavmot::run_app(
      argc, argv, "segmentation-tables", "paper Tables I and II for each segmentation method on simulator presets",
      [&](CLI::App& app) {
        app.add_option("--preset", presets, "simulator preset (repeatable)")->required();
        app.add_option("--seed", seed, "simulator seed")->capture_default_str();
        app.add_option("--frames", frames, "frames per sequence (0 = the preset's length)")->check(uavmot::non_negative_finite());
        app.add_flag("--truth-features", truth_features,
                     "ideal moving features from the ground truth instead of the motion layer");
        app.add_option("--config", config, "YAML file with a `segmentation:` section (defaults otherwise)")
            ->check(CLI::ExistingFile);
        return [&] {
          cv::setNumThreads(1);
          uavmot::segmentation::SimTablesRequest request;
          request.seed = seed;
          request.frames = frames;
          request.truth_features = truth_features;
          if (!config.empty()) {
            request.base = uavmot::segmentation::load_segmentation_options(
                uavmot::ConfigNode::load_file(config).child("segmentation"));
          }
          for (const auto& preset : presets) {
            request.preset = preset;
            std::printf("%s\n", uavmot::segmentation::format_tables(uavmot::segmentation::run_sim_tables(request)).c_str());
            std::fflush(stdout);
          }
          return uavmot::kExitOk;
        };
      });
}
