// Fault injection over the real processes of bringup/local.yaml, lossless mode: each component in
// turn is SIGKILLed, or SIGSTOPped (the launcher's watchdog, hang_timeout 3 s, then kills it), once
// the sink has written tracks past frame 40 of 120. The outcome is compared with an undisturbed run.
//
// What each component's fault leads to today (issue 20; docs/launch.md "Faults, component by
// component" explains why):
// - tracking, sink: respawned, and the result files are byte-identical to the undisturbed run's
//   (the tracker restores its saved state and reads the writers' recent history; the sink resumes
//   its files with --resume and the same history, skipping what they hold).
// - segmentation, motion: respawned, and the run ends (exit 0) with every frame after the fault,
//   but the files are not those of the undisturbed run: frames that had reached the killed process
//   but not its output are lost (motion also loses the previous frame and its features).
// - source: not respawned (stop_on_failure): the launch ends with exit 1; the files hold what was
//   written before, in complete lines.

#include <signal.h>

#include <thread>

#include <gtest/gtest.h>

#include "child_process.hpp"
#include "launched_chain.hpp"

namespace uavmot {
namespace {
using testing::binary;
using testing::ChildProcess;

enum class Outcome { Identical, Recovered, LaunchFails };

struct Fault {
  const char* component;
  int signal;
  Outcome expected;
  int domain;
};

std::string name_of(const ::testing::TestParamInfo<Fault>& info) {
  return std::string(info.param.component) + (info.param.signal == SIGKILL ? "_SIGKILL" : "_SIGSTOP");
}

const char* const kFiles[] = {"tracks.txt", "tracks_obb.csv", "regions.txt", "clusters.txt", "homographies.txt", "features.csv"};

class FaultInjection : public ::testing::TestWithParam<Fault> {
 protected:
  // One sequence and one undisturbed run for every case.
  static void SetUpTestSuite() {
    root_ = testing::fresh_dir("fault_injection");
    sequence_ = root_ + "/paper";
    ChildProcess sim({binary("uavmot-sim"), "--preset", "paper", "--seed", "3", "--frames", "120", "--out", sequence_},
                     root_ + "/sim.log");
    ASSERT_EQ(sim.wait(std::chrono::seconds(180)), 0) << sim.log();
    ChildProcess undisturbed({binary("uavmot"), "launch", testing::kLocalProfile, "--input", sequence_, "--out",
                              root_ + "/undisturbed", "--set", "domain=190", "--set", "hang_timeout=3"},
                             root_ + "/undisturbed.log");
    ASSERT_EQ(undisturbed.wait(std::chrono::seconds(300)), 0) << undisturbed.log();
  }
  static std::string root_, sequence_;
};
std::string FaultInjection::root_, FaultInjection::sequence_;

TEST_P(FaultInjection, ComponentFaultMidRun) {
  const Fault f = GetParam();
  ASSERT_FALSE(root_.empty());
  const std::string name = name_of({f, 0});
  const std::string out = root_ + "/" + name;
  ChildProcess launch({binary("uavmot"), "launch", testing::kLocalProfile, "--input", sequence_, "--out", out, "--set",
                       "domain=" + std::to_string(f.domain), "--set", "hang_timeout=3"},
                      root_ + "/" + name + ".log");
  int victim = -1;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(180);
  while (victim < 0 && std::chrono::steady_clock::now() < deadline && !launch.wait(std::chrono::milliseconds(0))) {
    const int pid = testing::launched_pid(launch.log(), f.component);
    if (pid > 0 && testing::last_frame_written(out + "/tracks_obb.csv") >= 40) {
      ASSERT_EQ(::kill(pid, f.signal), 0);
      victim = pid;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ASSERT_GT(victim, 0) << launch.log();
  const auto code = launch.wait(std::chrono::seconds(300));
  if (!code) {
    ::kill(victim, SIGKILL);
    launch.signal(SIGKILL);
  }
  ASSERT_TRUE(code.has_value()) << "the launch did not end\n" << launch.log();
  const std::string log = launch.log();
  if (f.signal == SIGSTOP) {
    EXPECT_NE(log.find(std::string(f.component) + " (pid " + std::to_string(victim) + ") hangs"), std::string::npos) << log;
  }
  std::string differing;
  for (const char* file : kFiles) {
    if (testing::read_file(out + "/" + file) != testing::read_file(root_ + "/undisturbed/" + file)) differing += std::string(" ") + file;
  }
  std::printf("%s at frame %d: launch exit %d; files differing from the undisturbed run:%s\n", name.c_str(),
              testing::last_frame_written(out + "/tracks_obb.csv"), *code, differing.empty() ? " none" : differing.c_str());
  switch (f.expected) {
    case Outcome::Identical:
      EXPECT_EQ(*code, 0) << log;
      EXPECT_EQ(differing, "") << log;
      break;
    case Outcome::Recovered:
      EXPECT_EQ(*code, 0) << log;
      EXPECT_EQ(testing::last_frame_written(out + "/tracks_obb.csv"),
                testing::last_frame_written(root_ + "/undisturbed/tracks_obb.csv"))
          << "the run did not reach the end\n" << log;
      break;
    case Outcome::LaunchFails:
      EXPECT_EQ(*code, 1) << log;
      EXPECT_NE(log.find(std::string(f.component) + " failed: stopping the launch"), std::string::npos) << log;
      break;
  }
}

INSTANTIATE_TEST_SUITE_P(EveryComponent, FaultInjection,
                         ::testing::Values(Fault{"tracking", SIGKILL, Outcome::Identical, 191},
                                           Fault{"tracking", SIGSTOP, Outcome::Identical, 192},
                                           Fault{"sink", SIGKILL, Outcome::Identical, 193},
                                           Fault{"sink", SIGSTOP, Outcome::Identical, 194},
                                           Fault{"segmentation", SIGKILL, Outcome::Recovered, 195},
                                           Fault{"segmentation", SIGSTOP, Outcome::Recovered, 196},
                                           Fault{"motion", SIGKILL, Outcome::Recovered, 197},
                                           Fault{"motion", SIGSTOP, Outcome::Recovered, 198},
                                           Fault{"source", SIGKILL, Outcome::LaunchFails, 199},
                                           Fault{"source", SIGSTOP, Outcome::LaunchFails, 200}),
                         name_of);

}  // namespace
}  // namespace uavmot
