// The tracker's hard cases, flown in the simulator with scripted vehicles (tests/scenarios/flights/):
// the real `uavmot sim`, `uavmot process` and `uavmot eval` programs, and each simulated vehicle's
// identity followed through the confirmed tracks frame by frame.

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <map>
#include <set>

#include <nlohmann/json.hpp>

#include "child_process.hpp"
#include "uavmot/build_paths/build_paths.hpp"
#include "uavmot/eval/predictions.hpp"
#include "uavmot/eval/sequence.hpp"

namespace uavmot {
namespace {

using testing::binary;
using testing::ChildProcess;
using testing::fresh_dir;

// Which confirmed track covers one simulated vehicle in one frame (0 = none).
struct Sighting {
  int64_t frame = 0;
  int64_t track = 0;
  bool moving = true;
};

struct Flight {
  std::map<int64_t, std::vector<Sighting>> timelines;  // moving vehicle's truth id -> every frame it is in view
  nlohmann::json eval;
  int64_t frames = 0;
};

void run(const std::vector<std::string>& argv, const std::string& log) {
  ChildProcess p(argv, log);
  const auto code = p.wait(std::chrono::minutes(5));
  ASSERT_TRUE(code.has_value()) << argv[0] << " did not finish:\n" << p.log();
  ASSERT_EQ(*code, 0) << p.log();
}

// A track covers a vehicle when its centre lies within half the vehicle's length of the true centre.
int64_t covering_track(const eval::GroundTruthObject& truth, const std::vector<eval::PredictedBox>& boxes) {
  int64_t best = 0;
  double best_distance = 0.5 * truth.box.length;
  for (const auto& b : boxes) {
    const double d = std::hypot(b.oriented->cx - truth.box.cx, b.oriented->cy - truth.box.cy);
    if (d <= best_distance) {
      best_distance = d;
      best = b.id;
    }
  }
  return best;
}

Flight fly(const std::string& name) {
  Flight flight;
  const std::string dir = fresh_dir("scripted_flight_" + name), seq = dir + "/seq", out = dir + "/out";
  const std::string scenario = build_paths::source_dir() + "/tests/scenarios/flights/" + name + ".yaml";
  run({binary("uavmot"), "sim", "--scenario", scenario, "--seed", "1", "--out", seq, "--quiet"}, dir + "/sim.log");
  run({binary("uavmot"), "process", seq, "--out", out, "--quiet"}, dir + "/process.log");
  run({binary("uavmot"), "eval", "--seq", seq, "--pred", out + "/tracks.txt", "--obb", out + "/tracks_obb.csv", "--json",
       out + "/eval.json"},
      dir + "/eval.log");
  if (::testing::Test::HasFatalFailure()) return flight;
  std::ifstream json(out + "/eval.json");
  flight.eval = nlohmann::json::parse(json);
  const eval::Sequence truth = eval::load_sequence(seq);
  const eval::Predictions tracks = eval::load_predictions({"", out + "/tracks_obb.csv", "", ""}, truth.info);
  flight.frames = truth.info.length;
  std::set<int64_t> ever_moving;
  for (const auto& [frame, objects] : truth.objects)
    for (const auto& o : objects)
      if (o.moving) ever_moving.insert(o.id);
  static const std::vector<eval::PredictedBox> none;
  for (const auto& [frame, objects] : truth.objects) {
    const auto found = tracks.boxes.find(frame);
    const auto& boxes = found == tracks.boxes.end() ? none : found->second;
    for (const auto& o : objects)
      if (ever_moving.count(o.id) && o.visibility >= 1.0) flight.timelines[o.id].push_back({frame, covering_track(o, boxes), o.moving});
  }
  return flight;
}

// Track ids that cover the vehicle in [from, to] (0 = not covered is left out), with frame counts.
std::map<int64_t, int> tracks_between(const std::vector<Sighting>& timeline, int64_t from, int64_t to) {
  std::map<int64_t, int> ids;
  for (const Sighting& s : timeline)
    if (s.frame >= from && s.frame <= to && s.track != 0) ++ids[s.track];
  return ids;
}

// Fraction of the frames in [from, to] in which the vehicle is covered by some track.
double coverage(const std::vector<Sighting>& timeline, int64_t from, int64_t to) {
  int in = 0, covered = 0;
  for (const Sighting& s : timeline) {
    if (s.frame < from || s.frame > to) continue;
    ++in;
    covered += s.track != 0 ? 1 : 0;
  }
  return in > 0 ? static_cast<double>(covered) / in : 0.0;
}

// Frames after which a new vehicle must be tracked: the tracker needs a few to confirm.
constexpr int64_t kConfirmFrames = 10;

std::string describe(const std::vector<Sighting>& timeline) {
  std::string text;
  int64_t start = 0, last_track = -1;
  for (size_t i = 0; i <= timeline.size(); ++i) {
    if (i < timeline.size() && timeline[i].track == last_track && timeline[i].frame == timeline[i - 1].frame + 1) continue;
    if (i > 0) text += std::to_string(last_track) + ":" + std::to_string(start) + "-" + std::to_string(timeline[i - 1].frame) + " ";
    if (i < timeline.size()) {
      start = timeline[i].frame;
      last_track = timeline[i].track;
    }
  }
  return text;  // "track:first-last ..." (track 0 = none)
}

void expect_common_quality(const Flight& f) {
  EXPECT_EQ(f.eval.at("false_alarms").at("on_parked").get<int>(), 0);
  EXPECT_LE(f.eval.at("completeness").at("under_segmented_rate").get<double>(), 0.0);
  EXPECT_LE(f.eval.at("completeness").at("over_segmented_rate").get<double>(), 0.02);
}

// Every vehicle stays on one track from kConfirmFrames on and is covered in >= 97 % of those
// frames; `ids` gets each vehicle's track.
void expect_one_track_each(const Flight& f, std::set<int64_t>& ids) {
  for (const auto& [truth, timeline] : f.timelines) {
    const auto tracks = tracks_between(timeline, kConfirmFrames, f.frames);
    ASSERT_EQ(tracks.size(), 1u) << "vehicle " << truth << " changed track: " << describe(timeline);
    ids.insert(tracks.begin()->first);
    EXPECT_GE(coverage(timeline, kConfirmFrames, f.frames), 0.97) << describe(timeline);
  }
}

// The faster car overtakes: for about 2 s the two drive side by side 10 px apart and form one
// region. Each keeps its track through the merge and after the split.
TEST(ScriptedFlights, OvertakingCarsKeepTheirIdentitiesThroughMergeAndSplit) {
  const Flight f = fly("overtaking");
  ASSERT_EQ(f.timelines.size(), 2u);
  std::set<int64_t> ids;
  ASSERT_NO_FATAL_FAILURE(expect_one_track_each(f, ids));
  for (const auto& [truth, timeline] : f.timelines)
    EXPECT_EQ(coverage(timeline, 125, 180), 1.0) << "side by side: " << describe(timeline);
  EXPECT_EQ(ids.size(), 2u) << "both cars on one track";
  expect_common_quality(f);
}

// Four cars 12 px apart bumper to bumper are four tracks, never one.
TEST(ScriptedFlights, ConvoyOfFourIsTrackedAsFour) {
  const Flight f = fly("convoy");
  ASSERT_EQ(f.timelines.size(), 4u);
  std::set<int64_t> ids;
  ASSERT_NO_FATAL_FAILURE(expect_one_track_each(f, ids));
  EXPECT_EQ(ids.size(), 4u);
  expect_common_quality(f);
  EXPECT_GE(f.eval.at("completeness").at("correct_rate").get<double>(), 0.95);
}

// The car drives out of the view ahead of the camera and falls back into it 3 s later: one
// track per visible stretch, no switch inside either, and nothing reported while it is away.
TEST(ScriptedFlights, VehicleLeavingAndReenteringTheViewHasNoIdSwitchWhileVisible) {
  const Flight f = fly("reentry");
  ASSERT_EQ(f.timelines.size(), 1u);
  const auto& timeline = f.timelines.begin()->second;
  std::vector<std::pair<int64_t, int64_t>> stretches;  // fully visible frames, first..last
  for (const Sighting& s : timeline) {
    if (stretches.empty() || s.frame != stretches.back().second + 1) stretches.push_back({s.frame, s.frame});
    else stretches.back().second = s.frame;
  }
  ASSERT_EQ(stretches.size(), 2u) << describe(timeline);
  for (const auto& [first, last] : stretches) {
    const int64_t from = first == 1 ? kConfirmFrames : first + kConfirmFrames;
    EXPECT_EQ(tracks_between(timeline, first, last).size(), 1u) << "an id switch while visible: " << describe(timeline);
    EXPECT_GE(coverage(timeline, from, last), 0.9) << describe(timeline);
  }
  // Away: no confirmed track anywhere (only parked cars are in view, and they get none).
  EXPECT_EQ(f.eval.at("false_alarms").at("false_alarms").get<int>(), 0);
  expect_common_quality(f);
}

// The car brakes, stands for 4 s and drives on: it is the same track before and after.
TEST(ScriptedFlights, StopAndGoVehicleIsNotLostWhileItStands) {
  const Flight f = fly("stop_and_go");
  ASSERT_EQ(f.timelines.size(), 1u);
  const auto& timeline = f.timelines.begin()->second;
  int64_t stop_first = 0, stop_last = 0;
  for (const Sighting& s : timeline) {
    if (!s.moving && stop_first == 0) stop_first = s.frame;
    if (!s.moving) stop_last = s.frame;
  }
  ASSERT_GT(stop_last - stop_first, 75) << "the script stands for 4 s";
  const auto before = tracks_between(timeline, kConfirmFrames, stop_first - 1);
  const auto after = tracks_between(timeline, stop_last + 1, f.frames);
  ASSERT_EQ(before.size(), 1u) << describe(timeline);
  ASSERT_EQ(after.size(), 1u) << describe(timeline);
  EXPECT_EQ(before.begin()->first, after.begin()->first) << "lost while standing: " << describe(timeline);
  EXPECT_GE(coverage(timeline, kConfirmFrames, stop_first - 1), 0.97) << describe(timeline);
  EXPECT_GE(coverage(timeline, stop_last + kConfirmFrames, f.frames), 0.9) << describe(timeline);
  expect_common_quality(f);
}

}  // namespace
}  // namespace uavmot
