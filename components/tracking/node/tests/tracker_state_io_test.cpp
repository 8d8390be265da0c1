// The tracker's state file: what is saved comes back (the origin included), and a file of another
// format (an earlier uavmot's unmarked CDR, a later version) is refused with a message, not misread.

#include "tracker_state_io.hpp"

#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tracker_statePubSubTypes.h"
#include "uavmot/core/error.hpp"
#include "uavmot/dds/cdr_sample.hpp"

namespace uavmot::tracking {
namespace {
namespace fs = std::filesystem;

TrackerState a_state() {
  TrackerState state;
  state.next_id = 8;
  state.frames_processed = 41;
  TrackRecord r;
  r.id = 7;
  r.state = TrackState::Confirmed;
  r.mean = {10.0, 20.0, 1.0, 0.5, 3.0, 12.0, 15.0};
  r.covariance[0] = 1.0;
  r.age = 30;
  r.hits = 28;
  r.anchor_box = {10.0, 20.0, 3.0, 12.0, 15.0};
  r.origin = {-35.25, 4.5};
  r.travel_from = {-20.5, 6.75};
  r.features.push_back({99, {0.25, -0.1}, 12});
  state.tracks.push_back(r);
  return state;
}

class TrackerStateFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = (fs::temp_directory_path() / ("tracker_state_io_" + std::to_string(::getpid()))).string();
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string file(const std::string& name) const { return dir_ + "/" + name; }
  void write(const std::string& path, const std::vector<uint8_t>& bytes) const {
    std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  }
  std::string dir_;
};

TEST_F(TrackerStateFileTest, WhatIsSavedComesBackOriginAndTravelIncluded) {
  save_snapshot(to_msg(a_state(), "uav1", 41), file("s.cdr"));
  const auto snapshot = load_snapshot(file("s.cdr"));
  ASSERT_TRUE(snapshot);
  EXPECT_EQ(snapshot->frame_index(), 41);
  std::string why;
  const auto state = from_msg(*snapshot, why);
  ASSERT_TRUE(state) << why;
  ASSERT_EQ(state->tracks.size(), 1u);
  EXPECT_EQ(state->tracks[0].origin, cv::Point2d(-35.25, 4.5));
  EXPECT_EQ(state->tracks[0].travel_from, cv::Point2d(-20.5, 6.75));
  EXPECT_EQ(state->tracks[0].features.at(0).frames_linked, 12u);
  EXPECT_FALSE(load_snapshot(file("absent.cdr")));
}

TEST_F(TrackerStateFileTest, AnEarlierUnmarkedFileOrAnotherVersionIsRefused) {
  auto snapshot = to_msg(a_state(), "uav1", 41);
  write(file("unmarked.cdr"), dds::to_cdr<msg::TrackerSnapshotPubSubType>(snapshot));  // as before version 2
  try {
    load_snapshot(file("unmarked.cdr"));
    ADD_FAILURE() << "an unmarked file was read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no 'UTRKSTAT' mark"), std::string::npos) << e.what();
  }
  save_snapshot(snapshot, file("saved.cdr"));
  std::ifstream in(file("saved.cdr"), std::ios::binary);
  std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (const uint8_t other : {2, 4}) {  // before travel_from, and a later one
    bytes[8] = other;  // the version's low byte
    write(file("other.cdr"), bytes);
    try {
      load_snapshot(file("other.cdr"));
      ADD_FAILURE() << "a version " << int(other) << " file was read";
    } catch (const InputError& e) {
      const std::string expected = "format version " + std::to_string(other) + "; this build reads version 3";
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    }
  }
}

TEST_F(TrackerStateFileTest, ANonFiniteOriginIsRefused) {
  TrackerState state = a_state();
  state.tracks[0].origin.x = std::nan("");
  std::string why;
  EXPECT_FALSE(from_msg(to_msg(state, "uav1", 41), why));
  EXPECT_NE(why.find("non-finite origin"), std::string::npos) << why;
  state = a_state();
  state.tracks[0].travel_from.y = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(from_msg(to_msg(state, "uav1", 41), why));
  EXPECT_NE(why.find("non-finite travel_from"), std::string::npos) << why;
}

}  // namespace
}  // namespace uavmot::tracking
