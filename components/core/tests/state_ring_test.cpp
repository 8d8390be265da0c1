// The ring of a stage's saved states (here motion's): which state a new process restores (the newest before the first
// frame it receives, passing over damaged ones), what a save removes, the legacy single file.
// States here are stand-ins ("frame 7" as text) read by a stand-in restore, so the choice is tested
// apart from the estimator (whose own save/restore is tested in components/motion/tests/saved_state_test.cpp and
// components/segmentation/tests/shift_check_test.cpp).

#include "uavmot/core/state_ring.hpp"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "uavmot/core/error.hpp"

namespace uavmot {
namespace {
namespace fs = std::filesystem;

std::vector<uint8_t> state_of(int64_t frame) {
  const std::string text = "frame " + std::to_string(frame);
  return {text.begin(), text.end()};
}
const std::vector<uint8_t> kDamaged = {'b', 'a', 'd'};

// The stand-in for MotionEstimator::restore_state + last_frame_index; records what it restored.
struct FakeRestore {
  std::vector<int64_t> tried;
  int64_t operator()(const std::vector<uint8_t>& bytes) {
    const std::string text(bytes.begin(), bytes.end());
    if (text.rfind("frame ", 0) != 0) {
      tried.push_back(-1);
      throw InputError("corrupt (checksum mismatch)");
    }
    tried.push_back(std::stoll(text.substr(6)));
    return tried.back();
  }
};

class StateRingTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = (fs::temp_directory_path() / ("state_ring_" + std::to_string(::getpid()) + "_" +
                                         ::testing::UnitTest::GetInstance()->current_test_info()->name()))
               .string();
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // The frames of uav1's state files on disk, oldest first.
  std::set<int64_t> on_disk() const { return StateRing(dir_, "motion_state", "uav1", 1000).frames(); }
  void write(const std::string& name, const std::vector<uint8_t>& bytes) const {
    std::ofstream(dir_ + "/" + name, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()),
                                                             static_cast<std::streamsize>(bytes.size()));
  }
  StateRing ring_with(std::initializer_list<int64_t> frames, int keep = 32) const {
    StateRing ring(dir_, "motion_state", "uav1", keep);
    for (int64_t f : frames) ring.save(f, state_of(f));
    return StateRing(dir_, "motion_state", "uav1", keep);  // as a new process lists them
  }

  std::string dir_;
};

TEST_F(StateRingTest, SavesOneFilePerFrameAndKeepsTheNewestN) {
  StateRing ring(dir_, "motion_state", "uav1", 3);
  for (int64_t f = 1; f <= 5; ++f) ring.save(f, state_of(f));
  EXPECT_EQ(ring.frames(), (std::set<int64_t>{3, 4, 5}));
  EXPECT_EQ(on_disk(), (std::set<int64_t>{3, 4, 5}));
  EXPECT_EQ(ring.path(5), dir_ + "/motion_state_uav1.0000000005.bin");
  EXPECT_TRUE(fs::exists(ring.path(5)));
  EXPECT_FALSE(fs::exists(ring.path(2)));
}

TEST_F(StateRingTest, ASaveRemovesTheStatesOfLaterFramesAnotherRunLeft) {
  ring_with({10, 11, 12, 13});
  StateRing ring(dir_, "motion_state", "uav1", 32);
  ring.save(9, state_of(9));  // this run continues from an earlier frame: 10-13 are not its states
  EXPECT_EQ(ring.frames(), (std::set<int64_t>{9}));
  EXPECT_EQ(on_disk(), (std::set<int64_t>{9}));
}

TEST_F(StateRingTest, OnlyThisStreamsStateFilesAreListedAndLeftoverTempFilesRemoved) {
  ring_with({4});
  write("motion_state_uav2.0000000007.bin", state_of(7));   // another stream
  write("motion_state_uav1.bin", state_of(3));              // the legacy single file: not a ring member
  write("motion_state_uav1.x0000008.bin", state_of(8));     // not a frame number
  write("motion_state_uav1.9.bin", state_of(9));            // not as the ring names frame 9
  write("motion_state_uav1.0000000005.bin.tmp", kDamaged);  // a write a crash cut short
  StateRing ring(dir_, "motion_state", "uav1", 32);
  EXPECT_EQ(ring.frames(), (std::set<int64_t>{4}));
  EXPECT_FALSE(fs::exists(dir_ + "/motion_state_uav1.0000000005.bin.tmp"));
  EXPECT_TRUE(fs::exists(dir_ + "/motion_state_uav2.0000000007.bin"));
}

TEST_F(StateRingTest, RestoresTheStateOfTheFrameBeforeTheFirstFrameReceived) {
  const auto ring = ring_with({5, 6, 7, 8, 9});
  FakeRestore restore;
  const auto choice = restore_before(ring, 8, std::ref(restore));
  ASSERT_TRUE(choice.restored);
  EXPECT_EQ(*choice.restored, 7);
  EXPECT_EQ(restore.tried, (std::vector<int64_t>{7}));
  EXPECT_EQ(choice.newer, (std::vector<int64_t>{8, 9}));
  EXPECT_TRUE(choice.refused.empty());
}

TEST_F(StateRingTest, WithoutThatFrameTheNewestOlderOneIsRestored) {
  const auto ring = ring_with({3, 5, 9});
  FakeRestore restore;
  const auto choice = restore_before(ring, 8, std::ref(restore));
  ASSERT_TRUE(choice.restored);
  EXPECT_EQ(*choice.restored, 5);
  EXPECT_EQ(choice.newer, (std::vector<int64_t>{9}));
}

TEST_F(StateRingTest, OnlyLaterStatesMeansStartingAfreshNotSkippingFrames) {
  const auto ring = ring_with({10, 11});
  FakeRestore restore;
  const auto choice = restore_before(ring, 5, std::ref(restore));
  EXPECT_FALSE(choice.restored);
  EXPECT_TRUE(restore.tried.empty()) << "a later state was restored";
  EXPECT_EQ(choice.newer, (std::vector<int64_t>{10, 11}));
}

TEST_F(StateRingTest, NoStatesMeansStartingAfresh) {
  const StateRing ring(dir_ + "/not_there", "motion_state", "uav1", 32);
  FakeRestore restore;
  const auto choice = restore_before(ring, 1, std::ref(restore));
  EXPECT_FALSE(choice.restored);
  EXPECT_TRUE(choice.newer.empty());
  EXPECT_TRUE(restore.tried.empty());
}

TEST_F(StateRingTest, ADamagedNewestStateFallsBackToAnOlderValidOne) {
  auto ring = ring_with({5, 6, 7});
  write("motion_state_uav1.0000000007.bin", kDamaged);
  FakeRestore restore;
  const auto choice = restore_before(ring, 8, std::ref(restore));
  ASSERT_TRUE(choice.restored);
  EXPECT_EQ(*choice.restored, 6);
  EXPECT_EQ(restore.tried, (std::vector<int64_t>{-1, 6}));
  ASSERT_EQ(choice.refused.size(), 1u);
  EXPECT_NE(choice.refused[0].find("motion_state_uav1.0000000007.bin"), std::string::npos) << choice.refused[0];
  EXPECT_NE(choice.refused[0].find("checksum mismatch"), std::string::npos) << choice.refused[0];
}

TEST_F(StateRingTest, AStateThatHoldsAnotherFrameThanItsNameIsRefused) {
  auto ring = ring_with({5, 6});
  write("motion_state_uav1.0000000006.bin", state_of(4));  // e.g. copied under the wrong name
  FakeRestore restore;
  const auto choice = restore_before(ring, 7, std::ref(restore));
  ASSERT_TRUE(choice.restored);
  EXPECT_EQ(*choice.restored, 5);
  ASSERT_EQ(choice.refused.size(), 1u);
  EXPECT_NE(choice.refused[0].find("holds frame 4"), std::string::npos) << choice.refused[0];
}

TEST_F(StateRingTest, EveryUsableStateDamagedIsAnErrorNamingTheFiles) {
  auto ring = ring_with({5, 6, 9});
  write("motion_state_uav1.0000000005.bin", kDamaged);
  write("motion_state_uav1.0000000006.bin", kDamaged);
  FakeRestore restore;
  try {
    restore_before(ring, 7, std::ref(restore));
    FAIL() << "damaged states were not refused";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("0000000005.bin"), std::string::npos) << what;
    EXPECT_NE(what.find("0000000006.bin"), std::string::npos) << what;
    EXPECT_NE(what.find("remove them"), std::string::npos) << what;
  }
  EXPECT_EQ(restore.tried, (std::vector<int64_t>{-1, -1})) << "the later state (9) must not be tried";
}

TEST_F(StateRingTest, TheLegacySingleFileBecomesTheRingsStateOfItsFrame) {
  ring_with({20});  // a later state stays: a new launch may need it
  write("motion_state_uav1.bin", state_of(12));
  StateRing ring(dir_, "motion_state", "uav1", 32);
  FakeRestore frame_of;
  const auto adopted = ring.adopt_legacy(std::ref(frame_of));
  ASSERT_TRUE(adopted);
  EXPECT_EQ(*adopted, 12);
  EXPECT_FALSE(fs::exists(ring.legacy_path()));
  EXPECT_EQ(ring.frames(), (std::set<int64_t>{12, 20}));
  EXPECT_EQ(on_disk(), (std::set<int64_t>{12, 20}));
  EXPECT_FALSE(ring.adopt_legacy(std::ref(frame_of))) << "no legacy file any more";
}

TEST_F(StateRingTest, ADamagedLegacyFileIsRefusedAndKept) {
  write("motion_state_uav1.bin", kDamaged);
  StateRing ring(dir_, "motion_state", "uav1", 32);
  FakeRestore frame_of;
  try {
    ring.adopt_legacy(std::ref(frame_of));
    FAIL() << "a damaged legacy file was taken";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(ring.legacy_path()), std::string::npos) << what;
    EXPECT_NE(what.find("remove it"), std::string::npos) << what;
  }
  EXPECT_TRUE(fs::exists(ring.legacy_path()));
  EXPECT_TRUE(ring.frames().empty());
}

TEST_F(StateRingTest, KeepingFewerThanOneStateIsRefused) {
  EXPECT_THROW(StateRing(dir_, "motion_state", "uav1", 0), InvalidArgument);
  EXPECT_THROW(StateRing(dir_, "motion_state", "uav1", -3), InvalidArgument);
}

}  // namespace
}  // namespace uavmot
