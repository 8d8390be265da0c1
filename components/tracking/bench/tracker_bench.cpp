// Tracker cost against the number of moving objects (synthetic scenes, camera motion, constant
// object density). Prints a Markdown table; the sequences are generated before timing.
//
//   build/bench/tracking_bench [--frames N] [--repeats R] [--objects N]

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "synthetic_scene.hpp"

using namespace uavmot;
using namespace uavmot::tracking;
using namespace uavmot::tracking::testing;

namespace {

std::vector<SyntheticFrame> make_sequence(int objects, int frames) {
  // Rows 30 px apart, cars 60 px apart along a row, alternate rows drive in opposite directions.
  const int per_row = std::max(1, static_cast<int>(std::ceil(std::sqrt(objects * 0.5))));
  const int rows = (objects + per_row - 1) / per_row;
  std::vector<ObjectPath> paths;
  for (int i = 0; i < objects; ++i) {
    const int row = i / per_row;
    const int col = i % per_row;
    ObjectPath o;
    o.truth_id = static_cast<uint64_t>(i + 1);
    const double speed = (row % 2 == 0 ? 1.0 : -1.0) * (1.0 + 0.1 * (row % 5));
    o.ground_centre = straight({100.0 + 1.6 * frames + 60.0 * col, 100.0 + 30.0 * row}, {speed, 0.05 * speed});
    paths.push_back(o);
  }
  SceneOptions opts;
  opts.image_width = 200 + 60 * per_row + 4 * frames;
  opts.image_height = 200 + 30 * rows + frames / 2;
  opts.static_features = 10 * objects;
  const cv::Point2d centre(opts.image_width / 2.0, opts.image_height / 2.0);
  SyntheticScene scene(paths, moving_camera({0.4, -0.2}, 0.02, 1.0002, centre), opts);
  std::vector<SyntheticFrame> sequence;
  for (int k = 0; k < frames; ++k) sequence.push_back(scene.next());
  return sequence;
}

}  // namespace

int main(int argc, char** argv) {
  int frames = 100;
  int repeats = 3;
  int only_objects = 0;  // --objects N: one size only (for profiling)
  for (int i = 1; i + 1 < argc; i += 2) {
    if (std::strcmp(argv[i], "--frames") == 0) frames = std::atoi(argv[i + 1]);
    if (std::strcmp(argv[i], "--repeats") == 0) repeats = std::atoi(argv[i + 1]);
    if (std::strcmp(argv[i], "--objects") == 0) only_objects = std::atoi(argv[i + 1]);
  }
  if (frames < 10 || repeats < 1) {
    std::fprintf(stderr, "usage: tracking_bench [--frames N>=10] [--repeats R>=1] [--objects N]\n");
    return 2;
  }
  std::printf("| moving objects | confirmed tracks (last frame) | ms / frame (best of %d) | us / object / frame |\n", repeats);
  std::printf("|---:|---:|---:|---:|\n");
  std::vector<int> sizes = {10, 20, 50, 100, 200, 300};
  if (only_objects > 0) sizes = {only_objects};
  for (const int objects : sizes) {
    const std::vector<SyntheticFrame> sequence = make_sequence(objects, frames);
    double best_ms = 1e30;
    size_t confirmed = 0;
    for (int r = 0; r < repeats; ++r) {
      Tracker tracker;
      const auto start = std::chrono::steady_clock::now();
      TrackList last;
      for (const auto& f : sequence) last = tracker.process(f.motion, f.segmentation);
      const auto stop = std::chrono::steady_clock::now();
      best_ms = std::min(best_ms, std::chrono::duration<double, std::milli>(stop - start).count() / frames);
      confirmed = static_cast<size_t>(std::count_if(last.tracks.begin(), last.tracks.end(),
                                                    [](const Track& t) { return t.state == TrackState::Confirmed; }));
    }
    std::printf("| %d | %zu | %.3f | %.2f |\n", objects, confirmed, best_ms, 1000.0 * best_ms / objects);
  }
  return 0;
}
