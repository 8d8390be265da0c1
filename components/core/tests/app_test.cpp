#include "uavmot/core/app.hpp"

#include <cstdlib>

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

}  // namespace
}  // namespace uavmot
