#include "uavmot/geo/clif_pos_sequence.hpp"

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "uavmot/build_paths/build_paths.hpp"
#include "uavmot/core/error.hpp"
#include "scratch_dir.hpp"

namespace uavmot::geo {
namespace {
namespace fs = std::filesystem;

fs::path fresh_dir(const std::string& name) {
  const fs::path dir = test_support::fresh_scratch_dir("clif_pos_sequence_" + name);
  fs::create_directories(dir / "jpg");
  fs::create_directories(dir / "pos");
  return dir;
}

// The median step, independently: over the 250 records, GPS week * 604800 + seconds of week,
// consecutive differences sorted with `sort -g` and the middle two averaged (awk): 0.630026 s.
TEST(ClifPosSequence, ClifFolderFrameRateFromGpsTimes) {
  const auto seq = read_clif_pos_sequence(build_paths::data_dir() + "/clif2007/jpg");
  ASSERT_TRUE(seq);
  EXPECT_EQ(seq->images, 250u);
  EXPECT_EQ(seq->records.size(), 250u);
  EXPECT_EQ(seq->missing, 0u);
  ASSERT_TRUE(seq->median_interval_s);
  EXPECT_NEAR(*seq->median_interval_s, 0.630026, 1e-5);
  ASSERT_TRUE(seq->fps());
  EXPECT_NEAR(*seq->fps(), 1.0 / 0.630026, 1e-4);
  EXPECT_DOUBLE_EQ(seq->records.front().latitude_deg, 40.0048617231066572);  // 000000-100006, the first image
}

TEST(ClifPosSequence, MissingRecordsAreCountedAndWeeksJoin) {
  const fs::path dir = fresh_dir("weeks");
  for (const char* name : {"a.jpg", "b.jpg", "c.jpg", "notes.txt"}) std::ofstream(dir / "jpg" / name) << "x";
  // a: last second of week 1451; c: 0.5 s into week 1452; b has no record.
  std::ofstream(dir / "pos" / "a.txt") << "0,0,0,40,-83,9000,604799.75,1451,0,0,0,3,-4,1\n";
  std::ofstream(dir / "pos" / "c.txt") << "0,0,0,40,-83,9000,0.5,1452,0,0,0,3,-4,1\n";
  const auto seq = read_clif_pos_sequence(dir / "jpg");
  ASSERT_TRUE(seq);
  EXPECT_EQ(seq->images, 3u);
  EXPECT_EQ(seq->missing, 1u);
  ASSERT_TRUE(seq->median_interval_s);
  EXPECT_NEAR(*seq->median_interval_s, 0.75, 1e-9);
}

TEST(ClifPosSequence, NoSiblingPosFolderOrNoRecordsIsNothing) {
  EXPECT_FALSE(read_clif_pos_sequence(build_paths::data_dir() + "/aphill"));
  EXPECT_FALSE(read_clif_pos_sequence(build_paths::data_dir() + "/aphill/aphill_short.ts"));
  const fs::path dir = fresh_dir("empty");
  std::ofstream(dir / "jpg" / "a.jpg") << "x";
  EXPECT_FALSE(read_clif_pos_sequence(dir / "jpg"));
}

TEST(ClifPosSequence, BrokenRecordIsAnInputError) {
  const fs::path dir = fresh_dir("broken");
  std::ofstream(dir / "jpg" / "a.jpg") << "x";
  std::ofstream(dir / "pos" / "a.txt") << "not,a,record\n";
  EXPECT_THROW(read_clif_pos_sequence(dir / "jpg"), InputError);
}

}  // namespace
}  // namespace uavmot::geo
