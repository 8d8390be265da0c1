#pragma once
// The shared shape of every uavmot-* main(): `--describe` for `uavmot --help`, CLI11 parsing,
// and user errors turned into one clear line on stderr and a non-zero exit.
//
//   int main(int argc, char** argv) {
//     return uavmot::run_app(argc, argv, "motion", "estimate camera and independent motion", [&](CLI::App& app) {
//       ... add options ...
//       return [&]() -> int { ... run ... return 0; };
//     });
//   }

#include <functional>
#include <string>

#include <CLI/CLI.hpp>

namespace uavmot {

// Exit codes shared by every process.
inline constexpr int kExitOk = 0;
inline constexpr int kExitFailure = 1;    // the run failed (e.g. a required peer never came)
inline constexpr int kExitBadInput = 2;   // bad arguments, configuration or input files

using AppBody = std::function<int()>;
using AppSetup = std::function<AppBody(CLI::App&)>;

int run_app(int argc, char** argv, const std::string& name, const std::string& description, const AppSetup& setup);

// Finite numbers >= 0 and > 0 (seconds, rates, sizes, counts), for every numeric option instead of
// CLI11's NonNegativeNumber / PositiveNumber: those let "nan" and "inf" through (every comparison
// with NaN is false), and a NaN timeout silently meant "wait forever".
CLI::Validator non_negative_finite();
CLI::Validator positive_finite();
// A finite number in [low, high], for floating-point options instead of CLI11's Range (same hole).
CLI::Validator finite_range(double low, double high);

// --state-keep of a node that keeps saved states (motion, segmentation): a whole number from 1 to
// 1000000, refused with a message that says what the number counts ("saved <what> states").
CLI::Validator states_kept_check(const std::string& what);

// OPENCV_FOR_THREADS_NUM=N (1..256) as cv::setNumThreads(N); run_app calls it first. OpenCV 4.6's
// TBB backend ignores the variable on its own: its workers stay, spin after every parallel_for_
// (connectedComponents, resize, ...), and took a third of the segmentation process's CPU time in
// the live chain, where five processes share two cores. Other values leave OpenCV's default,
// with a warning on stderr.
void apply_opencv_threads_from_environment();

}  // namespace uavmot
