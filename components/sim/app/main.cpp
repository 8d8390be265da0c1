// uavmot-sim: renders a simulated UAV sequence with ground truth as an MOTChallenge folder.
#include <cstdio>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "uavmot/core/error.hpp"
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "uavmot/sim/preview.hpp"
#include "uavmot/sim/scenario.hpp"
#include "uavmot/sim/simulator.hpp"
#include "uavmot/sim/sequence_writer.hpp"

int main(int argc, char** argv) {
  constexpr const char* kDescription = "render a simulated UAV sequence with exact ground truth (MOTChallenge folder)";
  CLI::App app{std::string("uavmot-sim: ") + kDescription};
  std::string preset, scenario_file, out_dir;
  uint64_t seed = 1;
  std::optional<int> frames;
  bool describe = false, quiet = false, list = false;
  app.add_flag("--describe", describe, "print one line describing this command and exit");
  app.add_flag("--list-presets", list, "print the preset names and exit");
  auto* preset_opt = app.add_option("--preset", preset, "built-in scenario: paper, lowsnr, fastcam, dense, slow, small, hd");
  auto* file_opt = app.add_option("--scenario", scenario_file, "scenario YAML file (see docs/sim.md)");
  preset_opt->excludes(file_opt);
  app.add_option("--seed", seed, "random seed; the same seed gives byte-identical output");
  app.add_option("--out", out_dir, "output folder (created)");
  app.add_option("--frames", frames, "override the number of frames")->check(CLI::Range(1, 100000));
  app.add_flag("-q,--quiet", quiet, "no progress on stderr");
  bool print_scenario = false;
  app.add_flag("--print-scenario", print_scenario, "print the resolved scenario as YAML and exit");
  std::string preview_file;
  int preview_frame = 1;
  double preview_scale = 1.0;
  app.add_option("--preview", preview_file, "instead of a sequence, write one frame with its ground truth drawn (PNG)");
  app.add_option("--preview-frame", preview_frame, "frame for --preview (1-based)")->check(CLI::PositiveNumber);
  app.add_option("--preview-scale", preview_scale, "enlargement for --preview")->check(CLI::Range(0.1, 8.0));
  std::vector<int> preview_crop;
  app.add_option("--preview-crop", preview_crop, "part of the frame for --preview: X Y WIDTH HEIGHT")->expected(4);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  if (describe) {
    std::cout << kDescription << "\n";
    return 0;
  }
  if (list) {
    for (const auto& n : uavmot::sim::preset_names()) std::cout << n << "\n";
    return 0;
  }
  try {
    if (preset.empty() && scenario_file.empty()) throw uavmot::InputError("give --preset NAME or --scenario FILE.yaml");
    if (out_dir.empty() && preview_file.empty() && !print_scenario) throw uavmot::InputError("give --out DIR");
    uavmot::sim::Scenario scenario;
    try {
      scenario = preset.empty() ? uavmot::sim::load_scenario_file(scenario_file) : uavmot::sim::preset_scenario(preset);
    } catch (const uavmot::InvalidArgument& e) {
      throw uavmot::InputError(e.what());
    }
    if (frames) scenario.frames = *frames;
    uavmot::sim::validate_scenario(scenario);
    if (print_scenario) {
      std::cout << uavmot::sim::scenario_to_yaml(scenario);
      return 0;
    }
    std::cerr << "uavmot-sim: scenario '" << scenario.name << "', " << scenario.frames << " frames "
              << scenario.camera.width << "x" << scenario.camera.height << ", seed " << seed << " -> " << out_dir << "\n";
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
  } catch (const uavmot::InputError& e) {
    std::cerr << "uavmot-sim: error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "uavmot-sim: error: " << e.what() << "\n";
    return 1;
  }
}
