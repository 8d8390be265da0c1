// Simulator throughput: scene setup, in-memory rendering per frame, and writing a whole
// sequence folder. Reports wall and CPU time (the build machine is shared and noisy).
//   build/bench/sim_bench --preset paper --frames 250 --out /tmp/sim_bench_seq
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <opencv2/imgcodecs.hpp>

#include "uavmot/sim/sequence_writer.hpp"
#include "uavmot/sim/simulator.hpp"

namespace {
struct Clock {
  std::chrono::steady_clock::time_point wall = std::chrono::steady_clock::now();
  std::clock_t cpu = std::clock();
  double wall_s() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - wall).count(); }
  double cpu_s() const { return static_cast<double>(std::clock() - cpu) / CLOCKS_PER_SEC; }
};
}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"sim_bench: simulator throughput"};
  std::string preset = "paper", out;
  int frames = 250;
  uint64_t seed = 1;
  app.add_option("--preset", preset);
  app.add_option("--frames", frames);
  app.add_option("--seed", seed);
  app.add_option("--out", out, "also time write_sequence into this folder (deleted first)");
  CLI11_PARSE(app, argc, argv);

  uavmot::sim::Scenario scenario = uavmot::sim::preset_scenario(preset);
  scenario.frames = frames;
  Clock setup;
  uavmot::sim::Simulator sim(scenario, seed);
  const double setup_wall = setup.wall_s(), setup_cpu = setup.cpu_s();
  std::vector<double> per_frame_ms;
  uavmot::sim::SimFrame frame;
  Clock render;
  while (true) {
    const auto t0 = std::chrono::steady_clock::now();
    if (!sim.next(frame)) break;
    per_frame_ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  }
  const double render_wall = render.wall_s(), render_cpu = render.cpu_s();
  std::sort(per_frame_ms.begin(), per_frame_ms.end());
  std::printf("preset %s, %dx%d, %d frames, seed %llu\n", preset.c_str(), scenario.camera.width, scenario.camera.height, frames,
              static_cast<unsigned long long>(seed));
  std::printf("setup (ground raster, roads, traffic warm-up): %.2f s wall, %.2f s CPU\n", setup_wall, setup_cpu);
  std::printf("render in memory: %.2f s wall, %.2f s CPU; per frame median %.1f ms, p95 %.1f ms (wall)\n", render_wall, render_cpu,
              per_frame_ms[per_frame_ms.size() / 2], per_frame_ms[per_frame_ms.size() * 95 / 100]);
  {
    // Cost of the pieces write_sequence adds per frame.
    cv::Mat mask16;
    frame.object_id_mask.convertTo(mask16, CV_16U);
    std::vector<uchar> bytes;
    Clock png;
    for (int i = 0; i < 20; ++i) cv::imencode(".png", mask16, bytes, {cv::IMWRITE_PNG_COMPRESSION, 1, cv::IMWRITE_PNG_STRATEGY, cv::IMWRITE_PNG_STRATEGY_RLE});
    std::printf("16-bit PNG id mask: %.1f ms wall, %.1f ms CPU per frame (%zu bytes)\n", png.wall_s() * 50.0, png.cpu_s() * 50.0, bytes.size());
  }
  if (!out.empty()) {
    std::filesystem::remove_all(out);
    Clock write;
    uavmot::sim::write_sequence(scenario, seed, out);
    std::printf("write_sequence (JPEG, masks, gt, mp4): %.2f s wall, %.2f s CPU\n", write.wall_s(), write.cpu_s());
  }
  return 0;
}
