// Runs every committed seed (corpus/<target>/) and every input that once crashed a fuzz target
// (regressions/<target>/, named after the bug it found) through the target again. In the ASan
// build this replays them under the sanitizers; in any build a regression crashes or throws here.

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "fuzz_targets.hpp"

namespace uavmot::fuzz {
namespace {

namespace fs = std::filesystem;
using Target = int (*)(const uint8_t*, size_t);

std::vector<uint8_t> read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Returns how many files it ran.
int replay(const std::string& name, Target target, const std::string& folder) {
  const fs::path dir = fs::path(UAVMOT_FUZZ_DIR) / folder / name;
  if (!fs::exists(dir)) return 0;
  int count = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (!entry.is_regular_file()) continue;
    const auto bytes = read_bytes(entry.path());
    SCOPED_TRACE(entry.path().string());
    EXPECT_EQ(target(bytes.data(), bytes.size()), 0);
    ++count;
  }
  return count;
}

struct Case {
  const char* name;
  Target target;
};

class FuzzReplay : public ::testing::TestWithParam<Case> {};

TEST_P(FuzzReplay, SeedsAndPastCrashesRunClean) {
  const auto [name, target] = GetParam();
  EXPECT_GE(replay(name, target, "corpus"), 2) << "every target keeps a seed corpus in tests/fuzz/corpus/" << name;
  replay(name, target, "regressions");
}

INSTANTIATE_TEST_SUITE_P(Targets, FuzzReplay,
                         ::testing::Values(Case{"mcap_reader", &mcap_reader}, Case{"sample_validators", &sample_validators},
                                           Case{"config", &config}, Case{"eval_files", &eval_files}),
                         [](const ::testing::TestParamInfo<Case>& param) { return std::string(param.param.name); });

}  // namespace
}  // namespace uavmot::fuzz
