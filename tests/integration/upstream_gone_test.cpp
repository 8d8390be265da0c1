// A component restarted after its stream had ended (its upstream wrote the end of stream and
// exited while it was down) would wait forever for writers that never come back. With
// --upstream-timeout (the launch profiles give it to respawned components) it gives up: exit 1
// after the timeout with an error that says why, and a sink keeps what it had written. Every
// component that reads the chain is started here with no writer on its domain.

#include <chrono>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "child_process.hpp"

namespace uavmot {
namespace {
using testing::binary;
using testing::ChildProcess;
constexpr int kDomain = 83;
constexpr double kTimeoutS = 2.0;

struct Reader {
  std::string name;
  std::vector<std::string> args;  // after the binary; --domain and --upstream-timeout are added
};

class UpstreamGone : public ::testing::TestWithParam<Reader> {};

std::string reader_name(const ::testing::TestParamInfo<Reader>& param) {
  std::string name = param.param.name;
  for (const auto& a : param.param.args) {
    if (a == "--downlink") name += "_downlink";
  }
  return name;
}

TEST_P(UpstreamGone, GivesUpAfterTheTimeoutWithExit1) {
  const Reader& r = GetParam();
  const std::string root = testing::fresh_dir("upstream_gone_" + r.name);
  std::vector<std::string> argv = {binary("uavmot-" + r.name)};
  for (auto a : r.args) argv.push_back(a == "OUT" ? root + "/results" : a);
  for (const std::string& a : std::vector<std::string>{"--domain", std::to_string(kDomain), "--mode", "lossless",
                                                         "--upstream-timeout", std::to_string(kTimeoutS)}) {
    argv.push_back(a);
  }
  const auto start = std::chrono::steady_clock::now();
  ChildProcess process(argv, root + "/" + r.name + ".log");
  const auto code = process.wait(std::chrono::seconds(60));
  const double took = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const std::string log = process.log();
  ASSERT_TRUE(code.has_value()) << r.name << " still waits for its upstream after 60 s\n" << log;
  EXPECT_EQ(*code, 1) << log;
  EXPECT_GE(took, kTimeoutS) << "gave up before the timeout\n" << log;
  EXPECT_NE(log.find("no writer of"), std::string::npos) << log;
  EXPECT_NE(log.find("(--upstream-timeout): the stream ended before this process (re)started"), std::string::npos) << log;
}

// A timeout that is not a finite number >= 0 is refused before anything starts (NaN used to pass
// CLI11's check and meant "wait forever").
TEST(UpstreamTimeout, NotAFiniteNonNegativeNumberIsRefused) {
  const std::string root = testing::fresh_dir("upstream_timeout_bad");
  for (const std::string bad : {"nan", "inf", "-1", "soon"}) {
    ChildProcess process({binary("uavmot-tracking"), "--domain", std::to_string(kDomain), "--upstream-timeout", bad},
                         root + "/tracking_" + bad + ".log");
    const auto code = process.wait(std::chrono::seconds(30));
    ASSERT_TRUE(code.has_value()) << bad << "\n" << process.log();
    EXPECT_EQ(*code, 2) << bad << "\n" << process.log();  // kExitBadInput
    EXPECT_NE(process.log().find("--upstream-timeout: not a"), std::string::npos) << process.log();
  }
}

INSTANTIATE_TEST_SUITE_P(ChainReaders, UpstreamGone,
                         ::testing::Values(Reader{"motion", {}}, Reader{"segmentation", {"--resume"}},
                                           Reader{"tracking", {}}, Reader{"sink", {"--out", "OUT", "--resume"}},
                                           Reader{"sink", {"--downlink", "--out", "OUT", "--resume"}},
                                           Reader{"downlink", {"--air-domain", "84", "--resume"}}),
                         reader_name);

}  // namespace
}  // namespace uavmot
