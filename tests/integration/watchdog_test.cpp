// The launcher's watchdog (hang_timeout, docs/launch.md) on a real launch of bringup/local.yaml:
// the tracker is stopped with SIGSTOP mid-run, so its process lives but its health reports on
// uavmot/health stop. The launcher must say so in its log, kill it and respawn it like a crashed
// one; the respawned tracker restores its state and the lossless run ends with the files of an
// undisturbed run. The components it held back (segmentation, motion, source waiting for its
// acknowledgements) keep reporting while they wait, so the watchdog leaves them alone.
// A component stopped as soon as it is started, before its first report, hangs too: without the
// watchdog's start-up rule it held the source waiting for its reader until the source gave up (4 x
// 30 s) and the launch failed.

#include <signal.h>

#include <cstdio>
#include <thread>

#include <gtest/gtest.h>

#include "child_process.hpp"
#include "launched_chain.hpp"

namespace uavmot {
namespace {
using testing::ChildProcess;

TEST(Watchdog, StoppedTrackerIsKilledAndRespawnedAndTheResultsAreUnchanged) {
  const std::string root = testing::fresh_dir("watchdog");
  std::string undisturbed_log;
  ASSERT_NO_FATAL_FAILURE(testing::run_undisturbed_paper(root, 120, {"domain=183", "hang_timeout=7"}, &undisturbed_log));
  EXPECT_EQ(undisturbed_log.find("hangs"), std::string::npos) << "the watchdog fired on an undisturbed run\n"
                                                              << undisturbed_log;

  ChildProcess launch(testing::local_launch(root + "/paper", root + "/stopped", {"domain=184", "hang_timeout=7"}),
                      root + "/stopped.log");
  const int stopped = testing::signal_when_written(launch, "tracking", root + "/stopped/tracks_obb.csv", 40, SIGSTOP).pid;
  ASSERT_GT(stopped, 0) << launch.log();
  // Noticed within the timeout and a few report periods (hang_timeout 7: above the 5 s a lossless
  // write() may block in Fast DDS, during which the components held back do not report).
  const std::string noticed = "tracking (pid " + std::to_string(stopped) + ") hangs: no health report for";
  const auto noticed_by = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (launch.log().find(noticed) == std::string::npos && std::chrono::steady_clock::now() < noticed_by) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  const bool was_noticed = launch.log().find(noticed) != std::string::npos;
  if (!was_noticed) ::kill(stopped, SIGKILL);  // do not leave a stopped process behind
  ASSERT_TRUE(was_noticed) << launch.log();

  ASSERT_EQ(launch.wait(std::chrono::seconds(300)), 0) << launch.log();
  const std::string log = launch.log();
  EXPECT_NE(log.find("tracking hung, killed by signal 9"), std::string::npos) << log;
  EXPECT_NE(log.find("respawning in"), std::string::npos) << log;
  EXPECT_NE(log.find("restored"), std::string::npos) << log;
  for (const char* name : {"source", "motion", "segmentation", "sink"}) {
    EXPECT_EQ(log.find(std::string(name) + " hung"), std::string::npos) << name << " was taken for hung\n" << log;
  }
  for (const char* file : {"tracks.txt", "tracks_obb.csv", "regions.txt", "homographies.txt"}) {
    EXPECT_EQ(testing::read_file(root + "/stopped/" + file), testing::read_file(root + "/undisturbed/" + file)) << file;
  }
}

TEST(Watchdog, AComponentStoppedBeforeItsFirstReportIsKilledAndRespawned) {
  const std::string root = testing::fresh_dir("watchdog_start");
  ASSERT_NO_FATAL_FAILURE(testing::run_undisturbed_paper(root, 60, {"domain=187", "hang_timeout=7"}));
  ChildProcess launch(testing::local_launch(root + "/paper", root + "/stopped", {"domain=188", "hang_timeout=7"}),
                      root + "/stopped.log");
  int stopped = -1;
  const auto started_by = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (stopped <= 0 && std::chrono::steady_clock::now() < started_by) {
    stopped = testing::launched_pid(launch.log(), "segmentation");
    if (stopped <= 0) std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  ASSERT_GT(stopped, 0) << launch.log();
  ASSERT_EQ(::kill(stopped, SIGSTOP), 0);
  const auto code = launch.wait(std::chrono::seconds(120));
  if (!code) {
    ::kill(stopped, SIGKILL);
    launch.signal(SIGKILL);
  }
  ASSERT_TRUE(code.has_value()) << "the launch did not end\n" << launch.log();
  ASSERT_EQ(*code, 0) << launch.log();
  const std::string log = launch.log();
  // Whichever came first, its start or its first report (the stop lands within a few ms of the
  // start, so nearly always before the report), the watchdog noticed it.
  EXPECT_NE(log.find("segmentation (pid " + std::to_string(stopped) + ") hangs: no health report"), std::string::npos) << log;
  EXPECT_NE(log.find("segmentation hung, killed by signal 9"), std::string::npos) << log;
  std::printf("stopped before its first report: %s\n",
              log.find("first health report of segmentation (pid " + std::to_string(stopped) + ")") == std::string::npos ? "yes" : "no");
  for (const char* file : {"tracks.txt", "tracks_obb.csv", "regions.txt", "homographies.txt"}) {
    EXPECT_EQ(testing::read_file(root + "/stopped/" + file), testing::read_file(root + "/undisturbed/" + file)) << file;
  }
}

}  // namespace
}  // namespace uavmot
