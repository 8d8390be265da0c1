// Benchmark of the motion layer against two baselines, on the same frames with exact ground truth:
//   uavmot         MotionEstimator (feature re-use, grid detection, LK + FB, RANSAC + Ceres)
//   uavmot-noceres the same without the Ceres refinement
//   videostab      cv::videostab::KeypointBasedMotionEstimator + MotionEstimatorRansacL2 (homography)
//   plain          goodFeaturesToTrack + calcOpticalFlowPyrLK + findHomography(RANSAC) per frame pair
// Frames: a simulator preset (--sim, e.g. hd = 1920 x 1080) or real CLIF 2007 texture warped along
// a smooth camera path (components/motion/testing); both give the exact homographies.
// Prints a markdown table: per-frame time (median, mean, p90) and mean transfer error vs truth.
#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <ctime>
#include <cstdio>
#include <functional>
#include <iostream>
#include <numeric>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>
#include <opencv2/videostab/global_motion.hpp>

#include "uavmot/build_paths/build_paths.hpp"
#include "uavmot/core/error.hpp"
#include "uavmot/core/yaml_config.hpp"
#include "uavmot/motion/motion_estimator.hpp"
#include "uavmot/sim/simulator.hpp"
#include "warped_sequence.hpp"

namespace {

using uavmot::Homography;

// CPU time of this thread: on a shared, loaded machine it measures the work on one core,
// where wall time would also count waiting for the CPU.
double thread_cpu_ms() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) * 1e3 + static_cast<double>(t.tv_nsec) * 1e-6;
}

struct Result {
  std::string name;
  std::vector<double> ms;       // thread CPU time
  std::vector<double> wall_ms;
  std::vector<double> error_px;  // per valid frame pair
  int valid = 0;
};

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[static_cast<size_t>(std::min<double>(static_cast<double>(v.size()) - 1, q * static_cast<double>(v.size())))];
}
double mean(const std::vector<double>& v) {
  return v.empty() ? 0.0 : std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size());
}

Homography from_mat(const cv::Mat& m) {
  cv::Mat d;
  m.convertTo(d, CV_64F);
  Homography h(d.ptr<double>());
  uavmot::normalize_homography(h);
  return h;
}

struct Frames {
  std::vector<cv::Mat> images;
  std::vector<Homography> truth;  // truth[k - 1]: frame k-1 -> k
  std::string description;
};

// Runs `estimate(k)` for k = 1..frames; frame 1 has no pair and is not counted.
Result measure(const std::string& name, const Frames& frames, const std::function<bool(int, Homography&)>& estimate) {
  Result r;
  r.name = name;
  const cv::Size size = frames.images.front().size();
  const int count = static_cast<int>(frames.images.size());
  for (int k = 1; k <= count; ++k) {
    Homography h = Homography::eye();
    const auto t0 = std::chrono::steady_clock::now();
    const double c0 = thread_cpu_ms();
    const bool ok = estimate(k, h);
    const double c1 = thread_cpu_ms();
    const auto t1 = std::chrono::steady_clock::now();
    if (k == 1) continue;  // no pair yet (uavmot's first call only detects)
    r.ms.push_back(c1 - c0);
    r.wall_ms.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
    if (ok) {
      ++r.valid;
      r.error_px.push_back(
          uavmot::mean_transfer_error(h, frames.truth[static_cast<size_t>(k - 1)], size.width, size.height));
    }
  }
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Motion layer benchmark: uavmot vs OpenCV videostab vs plain KLT + findHomography"};
  std::string clif = uavmot::build_paths::data_dir() + "/clif2007/jpg";
  int frames = 60, width = 1920, height = 1080, threads = 1, features = 1000;
  double speed = 3.0, rotation = 0.05, noise = 1.0, zoom = 0.0005;
  bool describe = false, only_uavmot = false, state = false;
  std::string sim_preset, config;
  uint64_t seed = 42;
  app.add_option("--clif", clif, "folder with the CLIF 2007 jpg frames (texture)");
  app.add_option("--frames", frames, "frames to process")->check(CLI::Range(3, 100000));
  app.add_option("--width", width, "frame width")->check(CLI::Range(64, 10000));
  app.add_option("--height", height, "frame height")->check(CLI::Range(64, 10000));
  app.add_option("--speed", speed, "camera speed, px/frame");
  app.add_option("--rotation", rotation, "camera rotation, deg/frame");
  app.add_option("--zoom", zoom, "relative scale change per frame");
  app.add_option("--noise", noise, "sensor noise sigma, grey levels");
  app.add_option("--threads", threads, "OpenCV threads (cv::setNumThreads)")->check(CLI::Range(1, 64));
  app.add_option("--baseline-features", features, "corners for the baselines (videostab default: 1000)");
  app.add_option("--sim", sim_preset, "render frames with this simulator preset (e.g. hd) instead of warped CLIF");
  app.add_option("--seed", seed, "simulator seed");
  app.add_option("--config", config, "YAML file with a motion: section for uavmot's options");
  app.add_flag("--only-uavmot", only_uavmot, "skip the no-Ceres variant and the baselines (for profiling)");
  app.add_flag("--state", state,
               "measure the saved state instead: its bytes, save_state() and restore_state() after every frame");
  app.add_flag("--describe", describe, "print a one-line description");
  CLI11_PARSE(app, argc, argv);
  if (describe) {
    std::cout << "benchmark the motion layer against OpenCV videostab and plain KLT\n";
    return 0;
  }
  try {
    cv::setNumThreads(threads);
    uavmot::motion::MotionOptions options;
    if (!config.empty()) {
      options = uavmot::motion::load_motion_options(uavmot::ConfigNode::load_file(config).child("motion"));
    }
    Frames input;
    uavmot::SceneInfo scene;
    if (!sim_preset.empty()) {
      uavmot::sim::Scenario scenario = uavmot::sim::preset_scenario(sim_preset);
      scenario.frames = frames;
      uavmot::sim::Simulator simulator(scenario, seed);
      scene = simulator.scene();
      uavmot::sim::SimFrame frame;
      while (simulator.next(frame)) {
        input.images.push_back(frame.image.clone());
        input.truth.push_back(frame.homography_from_previous);
      }
      input.description = "simulator preset '" + sim_preset + "' (seed " + std::to_string(seed) + "), " +
                          std::to_string(scenario.camera.width) + "x" + std::to_string(scenario.camera.height);
    } else {
      uavmot::motion::testing::WarpedSequenceOptions o;
      o.clif_folder = clif;
      o.frame_size = cv::Size(width, height);
      o.camera_speed_px = speed;
      o.rotation_deg_per_frame = rotation;
      o.zoom_per_frame = zoom;
      o.noise_sigma = noise;
      const uavmot::motion::testing::WarpedSequence seq(o);
      for (int k = 1; k <= frames; ++k) {
        input.images.push_back(seq.frame(k));
        input.truth.push_back(seq.true_homography(k));
      }
      char text[200];
      std::snprintf(text, sizeof text, "warped CLIF texture %dx%d, camera %.1f px/frame, %.2f deg/frame, noise %.1f",
                    width, height, speed, rotation, noise);
      input.description = text;
    }
    const std::vector<cv::Mat>& images = input.images;

    std::vector<Result> results;
    auto run_uavmot = [&](const std::string& name, bool refine) {
      uavmot::motion::MotionOptions variant = options;
      variant.refine = refine;
      uavmot::motion::MotionEstimator estimator(variant, scene);
      return measure(name, input, [&](int k, Homography& h) {
        uavmot::Frame f;
        f.index = k;
        f.image = images[static_cast<size_t>(k - 1)];
        const auto m = estimator.process(f);
        h = m.homography;
        return m.quality.valid;
      });
    };
    if (state) {
      // The saved state's size and what saving and restoring it costs (no file I/O: the node's
      // synced write is measured by uavmot-motion itself, docs/motion.md "Saved state").
      uavmot::motion::MotionEstimator estimator(options, scene);
      std::vector<double> save_ms, restore_ms, bytes;
      for (size_t k = 0; k < images.size(); ++k) {
        uavmot::Frame f;
        f.index = static_cast<int64_t>(k + 1);
        f.image = images[k];
        estimator.process(f);
        const auto t0 = std::chrono::steady_clock::now();
        const std::vector<uint8_t> saved = estimator.save_state();
        const auto t1 = std::chrono::steady_clock::now();
        uavmot::motion::MotionEstimator restored(options, scene);
        const auto t2 = std::chrono::steady_clock::now();
        restored.restore_state(saved);
        const auto t3 = std::chrono::steady_clock::now();
        if (k == 0) continue;  // the first frame has no features yet
        save_ms.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
        restore_ms.push_back(std::chrono::duration<double, std::milli>(t3 - t2).count());
        bytes.push_back(static_cast<double>(saved.size()));
      }
      std::printf("%s, %zu frames\n", input.description.c_str(), images.size());
      std::printf("state bytes: median %.0f, max %.0f; save_state() median %.2f ms, p90 %.2f ms; "
                  "restore_state() median %.2f ms, p90 %.2f ms\n",
                  percentile(bytes, 0.5), percentile(bytes, 1.0), percentile(save_ms, 0.5), percentile(save_ms, 0.9),
                  percentile(restore_ms, 0.5), percentile(restore_ms, 0.9));
      return 0;
    }
    results.push_back(run_uavmot("uavmot", true));
    if (only_uavmot) {
      const auto& r = results[0];
      std::printf("uavmot: CPU median %.2f ms, mean %.2f ms, p90 %.2f ms, max %.2f ms; error %.4f px\n",
                  percentile(r.ms, 0.5), mean(r.ms), percentile(r.ms, 0.9), percentile(r.ms, 1.0), mean(r.error_px));
      if (std::getenv("UAVMOT_BENCH_PER_FRAME")) {
        for (size_t i = 0; i < r.ms.size(); ++i) std::printf("frame %zu: %.2f ms\n", i + 2, r.ms[i]);
      }
      return 0;
    }
    results.push_back(run_uavmot("uavmot, no Ceres refinement", false));

    {
      using namespace cv::videostab;
      auto ransac = cv::makePtr<MotionEstimatorRansacL2>(MM_HOMOGRAPHY);
      KeypointBasedMotionEstimator estimator(ransac);
      estimator.setDetector(cv::GFTTDetector::create(features));
      results.push_back(measure("OpenCV videostab (KeypointBased + RansacL2)", input, [&](int k, Homography& h) {
        if (k == 1) return false;
        bool ok = false;
        const cv::Mat m = estimator.estimate(images[static_cast<size_t>(k - 2)], images[static_cast<size_t>(k - 1)], &ok);
        h = from_mat(m);
        return ok;
      }));
    }
    results.push_back(measure("plain GFTT + PyrLK + findHomography", input, [&](int k, Homography& h) {
      if (k == 1) return false;
      const cv::Mat& prev = images[static_cast<size_t>(k - 2)];
      const cv::Mat& cur = images[static_cast<size_t>(k - 1)];
      std::vector<cv::Point2f> p0, p1, a, b;
      cv::goodFeaturesToTrack(prev, p0, features, 0.01, 8);
      std::vector<unsigned char> status;
      std::vector<float> err;
      cv::calcOpticalFlowPyrLK(prev, cur, p0, p1, status, err, cv::Size(21, 21), 3);
      for (size_t i = 0; i < p0.size(); ++i) {
        if (status[i]) {
          a.push_back(p0[i]);
          b.push_back(p1[i]);
        }
      }
      if (a.size() < 4) return false;
      const cv::Mat m = cv::findHomography(a, b, cv::RANSAC, 3.0);
      if (m.empty()) return false;
      h = from_mat(m);
      return true;
    }));

    std::printf("%s, %zu frames, cv threads %d\n\n", input.description.c_str(), images.size(), threads);
    std::printf(
        "| method | CPU ms median | CPU ms mean | CPU ms p90 | CPU ms max | wall ms median | valid pairs | mean transfer "
        "error px | p95 error px |\n");
    std::printf("|---|---|---|---|---|---|---|---|---|\n");
    for (const auto& r : results) {
      std::printf("| %s | %.2f | %.2f | %.2f | %.2f | %.2f | %d/%zu | %.4f | %.4f |\n", r.name.c_str(),
                  percentile(r.ms, 0.5), mean(r.ms), percentile(r.ms, 0.9), percentile(r.ms, 1.0),
                  percentile(r.wall_ms, 0.5), r.valid, r.ms.size(), mean(r.error_px), percentile(r.error_px, 0.95));
    }
    std::printf("\nspeed-up of uavmot (mean CPU time): %.1fx vs videostab, %.1fx vs plain\n",
                mean(results[2].ms) / mean(results[0].ms), mean(results[3].ms) / mean(results[0].ms));
  } catch (const uavmot::InputError& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
