// Speed of the segmentation layer: 1080p frames with N moving car-like objects, one core.
//
//   uavmot segmentation-bench [--objects 50] [--frames 40] [--threads 1]
//
// Prints per method the median / 95th percentile of the time Segmenter::process (whole-frame
// path: clustering, crops, gradients, fusion, blobs) takes per frame: wall time, and the
// thread's CPU time (CLOCK_THREAD_CPUTIME_ID), which excludes time spent waiting for a core on
// a loaded machine. With --threads 1 OpenCV runs on the calling thread, so CPU time is the work.

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <opencv2/core.hpp>

#include "../tests/synthetic.hpp"
#include "uavmot/core/app.hpp"
#include "uavmot/segmentation/segmenter.hpp"

namespace seg = uavmot::segmentation;

namespace {

struct Workload {
  uavmot::Frame frame;
  uavmot::MotionEstimate motion;
  std::vector<uavmot::OrientedBox> truth;
};

// Objects matched one-to-one by a region with IoU >= 0.5 (a sanity figure, not the paper's metric).
int matched(const std::vector<uavmot::OrientedBox>& truth, const std::vector<uavmot::Region>& regions) {
  int count = 0;
  for (const auto& t : truth) {
    int hits = 0;
    for (const auto& r : regions) hits += uavmot::intersection_over_union(t, r.box) >= 0.5 ? 1 : 0;
    count += hits == 1 ? 1 : 0;
  }
  return count;
}

// Objects on a jittered grid over the frame (no overlaps), random heading and speed; every
// fifth object gets a neighbour driving beside it (an under-segmented pair).
Workload make_workload(int objects, uint64_t seed, const uavmot::SceneInfo& scene) {
  Workload w;
  w.frame.image = seg::testing::textured_background(cv::Size(1920, 1080), 100.0, 12.0, 2.5, seed);
  w.frame.index = static_cast<int64_t>(seed);
  w.motion.frame_index = w.frame.index;
  cv::RNG rng(seed * 7919 + 1);
  const double length = scene.metres_to_px(scene.vehicle_length_m), width = scene.metres_to_px(scene.vehicle_width_m);
  const int columns = 10, rows = (objects + columns - 1) / columns;
  uint64_t id = 1;
  for (int i = 0; i < objects; ++i) {
    const double cx = (i % columns + 0.5) * 1920.0 / columns + rng.uniform(-40.0, 40.0);
    const double cy = (i / columns + 0.5) * 1080.0 / rows + rng.uniform(-30.0, 30.0);
    const double angle = rng.uniform(-90.0, 90.0);
    const double speed = rng.uniform(0.5, 2.0);
    const cv::Vec2d velocity(speed * std::cos(angle * CV_PI / 180), speed * std::sin(angle * CV_PI / 180));
    uavmot::OrientedBox box{cx, cy, width, length, angle};
    seg::testing::draw_car(w.frame.image, box, rng.uniform(0, 2) ? 170 : 40);
    w.truth.push_back(box);
    for (auto& f : seg::testing::features_on(box, velocity, id)) w.motion.features.push_back(f);
    id += 10;
    if (i % 5 == 0) {  // a second car beside the first, same velocity
      const double off = width + 4.0;
      box.cx += -std::sin(angle * CV_PI / 180) * off;
      box.cy += std::cos(angle * CV_PI / 180) * off;
      seg::testing::draw_car(w.frame.image, box, 150);
      w.truth.push_back(box);
      for (auto& f : seg::testing::features_on(box, velocity, id)) w.motion.features.push_back(f);
      id += 10;
    }
  }
  return w;
}

double thread_cpu_ms() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) * 1e3 + static_cast<double>(t.tv_nsec) * 1e-6;
}

double percentile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  return v[static_cast<size_t>(q * static_cast<double>(v.size() - 1))];
}

}  // namespace

int run_bench(int objects, int frames, int threads) {
  cv::setNumThreads(threads);
  const uavmot::SceneInfo scene;  // GSD 0.35 m: cars about 13 x 5 px, as in the paper
  std::vector<Workload> workloads;
  for (int i = 0; i < 4; ++i) workloads.push_back(make_workload(objects, 100 + static_cast<uint64_t>(i), scene));

  std::printf("1920x1080, %d objects (+%d side-by-side partners), %d frames, %d thread(s)\n", objects,
              (objects + 4) / 5, frames, threads);
  {
    // What a split deployment would ship instead of the frame.
    seg::Segmenter segmenter(seg::SegmentationOptions{}, scene);
    const auto rois = segmenter.required_crops(workloads[0].motion, workloads[0].frame.image.size());
    long pixels = 0;
    for (const auto& r : rois) pixels += r.area();
    std::printf("crops per frame: %zu, %ld px (%.1f %% of the frame)\n\n", rois.size(), pixels,
                100.0 * static_cast<double>(pixels) / (1920.0 * 1080.0));
  }
  std::printf("| method | CPU median ms | CPU p95 ms | wall median ms | wall p95 ms | clusters | regions | objects matched (IoU >= 0.5) |\n"
              "|---|---|---|---|---|---|---|---|\n");
  for (auto method : uavmot::kSegmentationMethods) {
    seg::SegmentationOptions options;
    options.method = method;
    seg::Segmenter segmenter(options, scene);
    std::vector<double> ms, cpu_ms;
    size_t clusters = 0, regions = 0, truths = 0, hits = 0;
    for (int i = -2; i < frames; ++i) {  // two warm-up frames
      const Workload& w = workloads[static_cast<size_t>(i + 2) % workloads.size()];
      const double cpu_start = thread_cpu_ms();
      const auto start = std::chrono::steady_clock::now();
      const auto result = segmenter.process(w.frame, w.motion);
      const auto stop = std::chrono::steady_clock::now();
      const double cpu_stop = thread_cpu_ms();
      if (i < 0) continue;
      ms.push_back(std::chrono::duration<double, std::milli>(stop - start).count());
      cpu_ms.push_back(cpu_stop - cpu_start);
      clusters += result.clusters.size();
      regions += result.regions.size();
      truths += w.truth.size();
      hits += static_cast<size_t>(matched(w.truth, result.regions));
    }
    std::printf("| %s | %.2f | %.2f | %.2f | %.2f | %.1f | %.1f | %.1f %% |\n", uavmot::to_string(method),
                percentile(cpu_ms, 0.5), percentile(cpu_ms, 0.95), percentile(ms, 0.5), percentile(ms, 0.95),
                static_cast<double>(clusters) / frames,
                static_cast<double>(regions) / frames, 100.0 * static_cast<double>(hits) / static_cast<double>(truths));
  }
  return 0;
}

int main(int argc, char** argv) {
  int objects = 50, frames = 40, threads = 1;
  return uavmot::run_app(argc, argv, "segmentation-bench",
                         "benchmark: segmentation time per frame and method on synthetic 1080p frames", [&](CLI::App& app) {
                           app.add_option("--objects", objects, "moving car-like objects per frame")
                               ->capture_default_str()->check(CLI::Range(1, 10000));
                           app.add_option("--frames", frames, "frames timed per method")
                               ->capture_default_str()->check(CLI::Range(1, 100000));
                           app.add_option("--threads", threads, "OpenCV threads (1: CPU time is the work)")
                               ->capture_default_str()->check(CLI::Range(1, 256));
                           return [&] { return run_bench(objects, frames, threads); };
                         });
}
