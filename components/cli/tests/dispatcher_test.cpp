// The umbrella command as users call it: `uavmot --help`, `uavmot help SUB`, `uavmot SUB ...`,
// unknown subcommands. Runs the real build/bin/uavmot (under ASan in the asan stage, where the
// old `help SUB` read a destroyed argument vector).

#include <chrono>
#include <string>

#include <gtest/gtest.h>

#include "child_process.hpp"

namespace uavmot {
namespace {
using testing::binary;
using testing::ChildProcess;
using testing::fresh_dir;
using namespace std::chrono_literals;

struct Outcome {
  int code = -1;
  std::string output;
};

Outcome run(std::vector<std::string> args) {
  static int n = 0;
  const std::string log = fresh_dir("dispatcher") + "/run" + std::to_string(n++) + ".log";
  args.insert(args.begin(), binary("uavmot"));
  ChildProcess child(args, log);
  const auto code = child.wait(60s);
  return {code.value_or(-1), child.log()};
}

TEST(Dispatcher, HelpListsEverySubcommandWithItsDescription) {
  const Outcome r = run({"--help"});
  EXPECT_EQ(r.code, 0) << r.output;
  for (const char* sub : {"process", "launch", "motion", "segmentation", "tracking", "sim", "eval"}) {
    EXPECT_NE(r.output.find(std::string("  ") + sub + " "), std::string::npos) << sub << " missing from:\n" << r.output;
  }
}

TEST(Dispatcher, HelpSubIsTheSubcommandsOwnHelp) {
  const Outcome via_help = run({"help", "sim"});
  const Outcome direct = run({"sim", "--help"});
  EXPECT_EQ(via_help.code, 0) << via_help.output;
  EXPECT_NE(via_help.output.find("--preset"), std::string::npos) << via_help.output;
  EXPECT_EQ(via_help.output, direct.output);
}

TEST(Dispatcher, NoArgumentsPrintsUsageAndFails) {
  const Outcome r = run({});
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.output.find("usage: uavmot SUBCOMMAND"), std::string::npos) << r.output;
}

TEST(Dispatcher, UnknownSubcommandIsNamedAndFails) {
  const Outcome r = run({"fly-to-the-moon"});
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.output.find("'fly-to-the-moon' is not a uavmot subcommand"), std::string::npos) << r.output;
  const Outcome h = run({"help", "fly-to-the-moon"});
  EXPECT_EQ(h.code, 2) << h.output;
}

TEST(Dispatcher, PassesArgumentsAndExitCodeThrough) {
  // A bad option of the subcommand: its own error and exit code come back through the dispatcher.
  const Outcome r = run({"sim", "--preset", "no-such-preset", "--out", fresh_dir("dispatcher_sim")});
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("no-such-preset"), std::string::npos) << r.output;
}

TEST(Dispatcher, ANodesStateKeepIsRefusedWithWhatItCounts) {
  // Refused while parsing, before any DDS participant: exit 2 and a message naming the states.
  const Outcome segmentation = run({"segmentation", "--state-keep", "0"});
  EXPECT_EQ(segmentation.code, 2) << segmentation.output;
  EXPECT_NE(segmentation.output.find("'0' is not a number of saved segmentation states"), std::string::npos)
      << segmentation.output;
  const Outcome motion = run({"motion", "--state-keep", "2.5"});
  EXPECT_EQ(motion.code, 2) << motion.output;
  EXPECT_NE(motion.output.find("'2.5' is not a number of saved motion states"), std::string::npos) << motion.output;
}

}  // namespace
}  // namespace uavmot
