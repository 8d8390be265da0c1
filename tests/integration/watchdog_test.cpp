// The launcher's watchdog (hang_timeout, docs/launch.md) on a real launch of bringup/local.yaml:
// the tracker is stopped with SIGSTOP mid-run, so its process lives but its health reports on
// uavmot/health stop. The launcher must say so in its log, kill it and respawn it like a crashed
// one; the respawned tracker restores its state and the lossless run ends with the files of an
// undisturbed run. The components it held back (segmentation, motion, source waiting for its
// acknowledgements) keep reporting while they wait, so the watchdog leaves them alone.

#include <signal.h>

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

}  // namespace
}  // namespace uavmot
