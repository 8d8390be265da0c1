// uavmot-bench-classic: the classic OpenCV alternative to `uavmot process`, for the side-by-side
// benchmark (tools/bench_process.sh): GFTT + LK + findHomography, motion-compensated three-frame
// differencing (frame_difference.hpp) and a SORT-like tracker (sort_tracker.hpp). Reads the same
// inputs with the same frame source and writes MOTChallenge tracks.txt for `uavmot eval`.
// OpenCV's own threads are the only parallelism: --threads N is cv::setNumThreads(N).

#include <chrono>
#include <cstdio>
#include <filesystem>

#include <opencv2/core/utility.hpp>
#include <spdlog/spdlog.h>

#include "frame_difference.hpp"
#include "sort_tracker.hpp"
#include "uavmot/core/app.hpp"
#include "uavmot/core/output_file.hpp"
#include "uavmot/source/frame_source.hpp"

namespace uavmot {
namespace {

int classic_main(int argc, char** argv) {
  source::FrameSourceOptions input;
  std::string out_dir;
  int threads = 1;
  classic::DifferenceOptions detection;
  classic::SortOptions sort;
  return run_app(argc, argv, "bench-classic", "classic OpenCV chain (GFTT+LK+homography, frame differencing, SORT)", [&](CLI::App& app) {
    app.add_option("input", input.path, "video file, image folder or MOTChallenge sequence folder")->required();
    app.add_option("--out", out_dir, "output folder (tracks.txt)")->required();
    app.add_option("--threads", threads, "OpenCV threads (cv::setNumThreads)")->check(CLI::Range(1, 64))->capture_default_str();
    app.add_option("--count", input.max_frames, "number of frames (0 = all)")->check(uavmot::non_negative_finite());
    app.add_option("--threshold", detection.threshold, "grey-level difference threshold")->capture_default_str();
    app.add_option("--both", detection.both_differences, "1: AND of the differences with frames k-1 and k+1; 0: OR")
        ->capture_default_str();
    app.add_option("--min-area", detection.min_area_px, "smallest component, px")->capture_default_str();
    app.add_option("--max-area", detection.max_area_px, "largest component, px")->capture_default_str();
    app.add_option("--close", detection.close_px, "closing square, px")->capture_default_str();
    app.add_option("--min-hits", sort.min_hits, "matches before a track is reported")->capture_default_str();
    return [&]() -> int {
      cv::setNumThreads(threads);
      const auto start = std::chrono::steady_clock::now();
      auto frames = source::open_frame_source(input);
      std::filesystem::create_directories(out_dir);
      OutputFile tracks_file((std::filesystem::path(out_dir) / "tracks.txt").string());
      classic::FrameDifferenceDetector detector(detection);
      classic::SortTracker tracker(sort);
      auto write = [&](const classic::Detections& d) {
        std::string lines;
        for (const auto& t : tracker.update(d.boxes, d.homography_to_next)) {
          lines += fmt::format("{},{},{:.3f},{:.3f},{:.3f},{:.3f},1,-1,-1,-1\n", d.frame, t.id, t.box.x, t.box.y, t.box.width,
                               t.box.height);
        }
        tracks_file.append(lines);
      };
      Frame frame;
      int64_t done = 0;
      while (frames->next(frame)) {
        if (auto d = detector.push(static_cast<int>(frame.index), frame.image)) write(*d);
        ++done;
      }
      tracks_file.close();
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      spdlog::info("classic chain: {} frames in {:.2f} s ({:.1f} fps), {} OpenCV threads -> {}", done, seconds, done / seconds,
                   threads, out_dir);
      return kExitOk;
    };
  });
}

}  // namespace
}  // namespace uavmot

int main(int argc, char** argv) { return uavmot::classic_main(argc, argv); }
