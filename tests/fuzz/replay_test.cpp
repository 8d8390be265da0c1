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
#include "recorded_predictions.hpp"
#include "uavmot/build_paths/build_paths.hpp"
#include "uavmot/mcap/recover.hpp"
#include "scratch_dir.hpp"

namespace uavmot::fuzz {
namespace {

namespace fs = std::filesystem;
using Target = int (*)(const uint8_t*, size_t);

fs::path fuzz_dir() { return fs::path(build_paths::source_dir()) / "tests" / "fuzz"; }

std::vector<uint8_t> read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Returns how many files it ran.
int replay(const std::string& name, Target target, const std::string& folder) {
  const fs::path dir = fuzz_dir() / folder / name;
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
                                           Case{"config", &config}, Case{"eval_files", &eval_files},
                                           Case{"recording", &recording}, Case{"motion_state", &motion_state},
                                           Case{"segmentation_state", &segmentation_state}),
                         [](const ::testing::TestParamInfo<Case>& param) { return std::string(param.param.name); });

// The recording seeds must reach the whole path, not stop at the first check: the intact one scores
// as a recording of three frames, and the crashed one recovers to every complete chunk.
TEST(FuzzSeeds, RecordingSeedsAreRecordingsEvalReads) {
  const fs::path dir = fuzz_dir() / "corpus/recording";
  eval::SequenceInfo info;
  info.length = 10;
  info.width = 640;
  info.height = 480;
  const eval::Predictions intact = eval::load_recorded_predictions((dir / "tiny.mcap").string(), "", info);
  EXPECT_EQ(intact.boxes.size(), 3u);
  EXPECT_EQ(intact.homographies.size(), 3u);
  const fs::path repaired = test_support::scratch_path("fuzz_seed_repaired.mcap");
  const mcap::RecoverResult recovered = mcap::recover((dir / "tiny_crashed_no_summary.partial").string(), repaired.string());
  EXPECT_GE(recovered.messages, 2u);
  EXPECT_FALSE(eval::load_recorded_predictions(repaired.string(), "", info).boxes.empty());
  fs::remove(repaired);
}

}  // namespace
}  // namespace uavmot::fuzz
