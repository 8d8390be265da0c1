// The tracker's state outlives the launcher (and, being synced to disk, the host): a launch is
// stopped with SIGINT in the middle of a `paper` sequence, its tracker state kept in a folder of the
// user's (the launch variable tracker_state, not the launch's own run_dir). A new launch, with a new
// run_dir, continues from that state with the remaining frames, starting 10 frames before the one
// the state holds (start=K-10: motion needs a few frames of history before it finds the moving
// objects again; the tracker skips every frame up to K). The tracker restores the state, new tracks
// get ids after the restored ones (none is reused), and objects in view before the stop keep their
// ids after it. Not byte-identical: motion's state (previous frame, features tracked over many
// frames) is not saved, so its detections after the restart differ from an uninterrupted run's.

#include <signal.h>

#include <filesystem>
#include <regex>
#include <set>
#include <thread>

#include <gtest/gtest.h>

#include "child_process.hpp"
#include "launched_chain.hpp"
#include "obb_rows.hpp"

namespace uavmot {
namespace {
using testing::ChildProcess;
namespace fs = std::filesystem;

using testing::last_frame_written;
using testing::read_tracks;

TEST(TrackerResume, NewLaunchContinuesFromTheSavedStateWithTheSameTrackIds) {
  const std::string root = testing::fresh_dir("tracker_resume");
  const std::string sequence = root + "/paper";
  const std::string state = root + "/tracker_state";  // the user's folder, outside any launch's run_dir
  ASSERT_NO_FATAL_FAILURE(testing::run_undisturbed_paper(root, 160, {"domain=180"}));

  // First launch: stopped as a whole (SIGINT, as at shutdown of the host) once tracks past frame 70 are written.
  ChildProcess first(testing::local_launch(sequence, root + "/first", {"domain=181", "tracker_state=" + state}),
                     root + "/first.log");
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(180);
  while (std::chrono::steady_clock::now() < deadline && last_frame_written(root + "/first/tracks_obb.csv") < 70 &&
         !first.wait(std::chrono::milliseconds(0))) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ASSERT_GE(last_frame_written(root + "/first/tracks_obb.csv"), 70) << first.log();
  first.signal(SIGINT);
  ASSERT_TRUE(first.wait(std::chrono::seconds(120))) << first.log();
  std::smatch m;
  const std::string first_log = first.log();
  // The tracker's line, not motion's ("motion state saved at frame ..."), which may come first and
  // name a later frame: motion runs ahead of tracking.
  ASSERT_TRUE(std::regex_search(first_log, m, std::regex(R"(\[tracking\] \[info\] stream 'uav1': state saved at frame (\d+))")))
      << first_log;
  const int saved = std::stoi(m[1]);
  ASSERT_GE(saved, 70);
  ASSERT_LT(saved, 150) << "the first launch ran (almost) to the end: nothing left to continue";
  ASSERT_TRUE(fs::exists(state + "/tracker_state_uav1.cdr"));

  // Second launch: a new launcher (new run_dir), the same state folder, the remaining frames.
  ChildProcess second(testing::local_launch(sequence, root + "/second",
                                            {"domain=182", "tracker_state=" + state, "start=" + std::to_string(saved - 10)}),
                      root + "/second.log");
  ASSERT_EQ(second.wait(std::chrono::seconds(300)), 0) << second.log();
  const std::string second_log = second.log();
  ASSERT_TRUE(std::regex_search(second_log, m, std::regex("restored \\d+ tracks at frame " + std::to_string(saved) +
                                                          R"( \(next id (\d+)\))")))
      << second_log;
  const int next_id = std::stoi(m[1]);

  const auto before = read_tracks(root + "/undisturbed/tracks.txt");
  const auto after = read_tracks(root + "/second/tracks.txt");
  ASSERT_FALSE(after.empty()) << second.log();
  EXPECT_EQ(after.begin()->first, saved + 1) << "the second launch's first frame with tracks";
  // Ids go on from the restored state: an id below next_id is one the first launch gave out, to a
  // confirmed track or to a tentative one that the restored state carries (tracks_obb.csv has every
  // state; tracks.txt only the confirmed).
  std::set<int> first_ids;
  for (const auto& row : testing::read_obb_rows(root + "/first/tracks_obb.csv")) first_ids.insert(row.id);
  for (const auto& [frame, tracks] : after) {
    for (const auto& [id, box] : tracks) {
      EXPECT_TRUE(id >= next_id || first_ids.count(id)) << "frame " << frame << ": id " << id << " reused";
    }
  }
  // Objects in view before the stop keep their ids after it.
  const int probe = saved + 15;
  ASSERT_TRUE(before.count(probe) && before.count(saved - 5)) << "no confirmed tracks around the stop";
  const auto [compared, kept] = testing::ids_kept(before, after, probe, saved - 5);
  std::printf("stopped at frame %d; ids kept across the new launch: %d/%d\n", saved, kept, compared);
  ASSERT_GT(compared, 2) << "too few tracks span the stop to judge";
  // A few tracks lose their object while motion finds it again (see above) and end.
  EXPECT_GE(kept, compared * 8 / 10) << kept << " of " << compared << " tracks kept their ids";
}

}  // namespace
}  // namespace uavmot
