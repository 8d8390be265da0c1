// uavmot-sim: renders a simulated UAV sequence with ground truth as an MOTChallenge folder.
#include <cstdio>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "uavmot/core/app.hpp"
#include "uavmot/core/error.hpp"
#include "uavmot/sim/preview.hpp"
#include "uavmot/sim/scenario.hpp"
#include "uavmot/sim/simulator.hpp"
#include "uavmot/sim/sequence_writer.hpp"

namespace {

int sim_main(int argc, char** argv) {
  // Options outlive the setup lambda: the body reads them.
  std::string preset, scenario_file, out_dir, preview_file;
  uint64_t seed = 1;
  std::optional<int> frames;
  bool quiet = false, list = false, print_scenario = false, vary = false;
  int preview_frame = 1;
  double preview_scale = 1.0;
  std::vector<int> preview_crop;
  return uavmot::run_app(argc, argv, "sim", "render a simulated UAV sequence with exact ground truth (MOTChallenge folder)",
                         [&](CLI::App& app) -> uavmot::AppBody {
    app.add_flag("--list-presets", list, "print the preset names and exit");
    auto* preset_opt = app.add_option("--preset", preset, "built-in scenario: paper, lowsnr, fastcam, dense, slow, small, hd, urban3d, oblique");
    auto* file_opt = app.add_option("--scenario", scenario_file, "scenario YAML file (see docs/sim.md)");
    preset_opt->excludes(file_opt);
    app.add_option("--seed", seed, "random seed; the same seed gives byte-identical output");
    app.add_option("--out", out_dir, "output folder (created)");
    app.add_option("--frames", frames, "override the number of frames")->check(CLI::Range(1, 100000));
    app.add_flag("--vary", vary,
                 "redraw the scene around the preset from the seed: road layout, asphalt, vehicle mix, colours and sizes, sun, "
                 "camera heading, speed, GSD, frame rate and resolution, blur, noise, JPEG quality (docs/sim.md)");
    app.add_flag("-q,--quiet", quiet, "no progress on stderr");
    app.add_flag("--print-scenario", print_scenario, "print the resolved scenario as YAML and exit");
    app.add_option("--preview", preview_file, "instead of a sequence, write one frame with its ground truth drawn (PNG)");
    app.add_option("--preview-frame", preview_frame, "frame for --preview (1-based)")->check(uavmot::positive_finite());
    app.add_option("--preview-scale", preview_scale, "enlargement for --preview")->check(uavmot::finite_range(0.1, 8.0));
    app.add_option("--preview-crop", preview_crop, "part of the frame for --preview: X Y WIDTH HEIGHT")->expected(4);
    return [&]() -> int {
      if (list) {
        for (const auto& n : uavmot::sim::preset_names()) std::cout << n << "\n";
        return 0;
      }
      if (preset.empty() && scenario_file.empty()) throw uavmot::InputError("give --preset NAME or --scenario FILE.yaml");
      if (out_dir.empty() && preview_file.empty() && !print_scenario) throw uavmot::InputError("give --out DIR");
      uavmot::sim::Scenario scenario =
          preset.empty() ? uavmot::sim::load_scenario_file(scenario_file) : uavmot::sim::preset_scenario(preset);
      if (vary) scenario = uavmot::sim::vary_scenario(scenario, seed);
      if (frames) scenario.frames = *frames;
      uavmot::sim::validate_scenario(scenario);
      if (print_scenario) {
        std::cout << uavmot::sim::scenario_to_yaml(scenario);
        return 0;
      }
      std::cerr << "uavmot-sim: scenario '" << scenario.name << "', " << scenario.frames << " frames "
                << scenario.camera.width << "x" << scenario.camera.height << ", seed " << seed << (vary ? " (varied by the seed)" : "")
                << " -> " << out_dir << "\n";
      if (!preview_file.empty()) {
        if (preview_frame > scenario.frames) throw uavmot::InputError("--preview-frame is beyond the last frame");
        scenario.frames = preview_frame;
        uavmot::sim::Simulator sim(scenario, seed);
        uavmot::sim::SimFrame frame;
        while (sim.next(frame)) {
        }
        uavmot::sim::PreviewOptions options;
        options.scale = preview_scale;
        if (preview_crop.size() == 4) options.crop = cv::Rect(preview_crop[0], preview_crop[1], preview_crop[2], preview_crop[3]);
        if (!cv::imwrite(preview_file, uavmot::sim::draw_ground_truth(frame, options)))
          throw uavmot::InputError("cannot write '" + preview_file + "'");
        return 0;
      }
      int last_percent = -1;
      const auto progress = [&](int done, int total) {
        if (quiet) return;
        const int percent = 100 * done / total;
        if (percent / 10 != last_percent / 10 || done == total) {
          std::cerr << "uavmot-sim: frame " << done << "/" << total << "\n";
          last_percent = percent;
        }
      };
      const auto summary = uavmot::sim::write_sequence(scenario, seed, out_dir, progress);
      std::cerr << "uavmot-sim: wrote " << summary.frames << " frames, " << summary.vehicles << " vehicles ("
                << summary.moving_vehicles << " moving, " << summary.parked_vehicles << " parked), "
                << summary.moving_instances << " moving instances\n";
      return 0;
    };
  });
}

}  // namespace

int main(int argc, char** argv) { return sim_main(argc, argv); }
