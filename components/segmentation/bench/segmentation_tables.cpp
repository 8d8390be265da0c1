// Paper Tables I and II for clustering, korn, morphological, lbp and fusion on simulated
// sequences (docs/segmentation.md keeps the output):
//
//   build/bin/uavmot-segmentation-tables --preset paper --preset dense --seed 1 [--truth-features]

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <opencv2/core.hpp>

#include "sim_tables.hpp"
#include "uavmot/core/app.hpp"
#include "uavmot/segmentation/segmentation_options.hpp"

int main(int argc, char** argv) {
  return uavmot::run_app(
      argc, argv, "segmentation-tables", "paper Tables I and II for each segmentation method on simulator presets",
      [](CLI::App& app) -> uavmot::AppBody {
        struct Args {
          std::vector<std::string> presets;
          uint64_t seed = 1;
          int frames = 0;
          std::string config;
          bool truth_features = false;
        };
        auto args = std::make_shared<Args>();
        app.add_option("--preset", args->presets, "simulator preset (repeatable)")->required();
        app.add_option("--seed", args->seed, "simulator seed")->capture_default_str();
        app.add_option("--frames", args->frames, "frames per sequence (0 = the preset's length)")
            ->check(uavmot::non_negative_finite());
        app.add_flag("--truth-features", args->truth_features,
                     "ideal moving features from the ground truth instead of the motion layer");
        app.add_option("--config", args->config, "YAML file with a `segmentation:` section (defaults otherwise)")
            ->check(CLI::ExistingFile);
        return [args] {
          cv::setNumThreads(1);
          uavmot::segmentation::SimTablesRequest request;
          request.seed = args->seed;
          request.frames = args->frames;
          request.truth_features = args->truth_features;
          if (!args->config.empty()) {
            request.base = uavmot::segmentation::load_segmentation_options(
                uavmot::ConfigNode::load_file(args->config).child("segmentation"));
          }
          for (const auto& preset : args->presets) {
            request.preset = preset;
            std::printf("%s\n", uavmot::segmentation::format_tables(uavmot::segmentation::run_sim_tables(request)).c_str());
            std::fflush(stdout);
          }
          return uavmot::kExitOk;
        };
      });
}
