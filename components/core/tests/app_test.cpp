#include "uavmot/core/app.hpp"

#include <cstdlib>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core/utility.hpp>

namespace uavmot {
namespace {

int threads_seen_by_app(const char* env_value) {
  if (env_value) ::setenv("OPENCV_FOR_THREADS_NUM", env_value, 1); else ::unsetenv("OPENCV_FOR_THREADS_NUM");
  char name[] = "uavmot-test";
  char* argv[] = {name};
  return run_app(1, argv, "test", "test", [](CLI::App&) { return [] { return cv::getNumThreads(); }; });
}

TEST(App, OpenCvThreadsFromTheEnvironmentAreApplied) {
  const int default_threads = cv::getNumThreads();
  EXPECT_EQ(threads_seen_by_app("1"), 1);
  EXPECT_EQ(threads_seen_by_app("3"), 3);
  cv::setNumThreads(default_threads);
  // Not a number, or out of range: OpenCV's setting stays as it was.
  EXPECT_EQ(threads_seen_by_app("many"), default_threads);
  EXPECT_EQ(threads_seen_by_app("0"), default_threads);
  EXPECT_EQ(threads_seen_by_app(nullptr), default_threads);
  ::unsetenv("OPENCV_FOR_THREADS_NUM");
}

// Runs an app with one double option checked by `validator`; returns the exit code, or 101 when
// the body ran with the value parsed.
int exit_code_for(const CLI::Validator& validator, const std::string& value) {
  std::string name = "uavmot-test", flag = "--seconds", text = value;
  std::vector<char*> argv = {name.data(), flag.data(), text.data()};
  return run_app(static_cast<int>(argv.size()), argv.data(), "test", "test", [&](CLI::App& app) {
    static double seconds = 0.0;
    app.add_option("--seconds", seconds)->check(validator);
    return [] { return 101; };
  });
}

TEST(App, NumericOptionsRefuseNanAndInfinityWithTheBadInputCode) {
  for (const std::string bad : {"nan", "NaN", "inf", "-inf", "-1", "soon", ""}) {
    EXPECT_EQ(exit_code_for(non_negative_finite(), bad), kExitBadInput) << bad;
    EXPECT_EQ(exit_code_for(positive_finite(), bad), kExitBadInput) << bad;
  }
  EXPECT_EQ(exit_code_for(positive_finite(), "0"), kExitBadInput);
  EXPECT_EQ(exit_code_for(non_negative_finite(), "0"), 101);
  EXPECT_EQ(exit_code_for(non_negative_finite(), "2.5"), 101);
  EXPECT_EQ(exit_code_for(positive_finite(), "1e-3"), 101);
  for (const std::string bad : {"nan", "inf", "-0.1", "1.5", "x"}) {
    EXPECT_EQ(exit_code_for(finite_range(0.0, 1.0), bad), kExitBadInput) << bad;
  }
  EXPECT_EQ(exit_code_for(finite_range(0.0, 1.0), "0"), 101);
  EXPECT_EQ(exit_code_for(finite_range(0.0, 1.0), "1"), 101);
  EXPECT_EQ(exit_code_for(finite_range(0.0, 1.0), "0.5"), 101);
}

TEST(App, HelpExitsZeroAndAnUnknownOptionExitsWithTheBadInputCode) {
  std::string name = "uavmot-test", help = "--help", unknown = "--no-such-option";
  auto run = [&](std::string& arg) {
    std::vector<char*> argv = {name.data(), arg.data()};
    return run_app(2, argv.data(), "test", "test", [](CLI::App&) { return [] { return 101; }; });
  };
  EXPECT_EQ(run(help), kExitOk);
  EXPECT_EQ(run(unknown), kExitBadInput);
}

}  // namespace
}  // namespace uavmot
