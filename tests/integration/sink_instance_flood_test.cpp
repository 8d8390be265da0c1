// A rogue participant publishes samples of 20 made-up stream ids on the sink's topics before the
// real chain starts. The sink's readers keep at most 8 stream ids (max_instances); Fast DDS 2.9
// never evicts an alive one, so without a filter the real stream's samples are rejected by DDS
// before the sink's stream gate sees them, and the run never ends. With --stream-id the readers
// filter on the key (a ContentFilteredTopic, evaluated before a sample enters the history): the
// run writes exactly what an undisturbed run writes.

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <vector>

#include <gtest/gtest.h>

#include "child_process.hpp"
#include "motionPubSubTypes.h"
#include "segmentationPubSubTypes.h"
#include "tracksPubSubTypes.h"
#include "uavmot/dds/chain_convert.hpp"
#include "uavmot/dds/participant.hpp"

namespace uavmot {
namespace {
using testing::binary;
using testing::ChildProcess;

constexpr int kForgedIds = 20;

// KEY=value of the sequence's seqinfo.ini, as `uavmot launch --input` reads gsd and fps.
std::string seqinfo(const std::string& sequence, const std::string& key) {
  std::ifstream in(sequence + "/seqinfo.ini");
  for (std::string line; std::getline(in, line);) {
    if (line.rfind(key + "=", 0) == 0) return line.substr(key.size() + 1);
  }
  return "";
}

// Samples of ids forged0..19 on motion, segmentation and tracks, acknowledged by the sink. The
// rogue's writers stay alive, so their instances stay alive in the sink's readers.
struct Rogue {
  // A writer holds at most 10 instances (Fast DDS's default max_instances): one set per 10 ids.
  explicit Rogue(int domain) : participant(options(domain)) {
    for (int i = 0; i < kForgedIds; i += 10) {
      motions.push_back(participant.make_writer<msg::MotionEstimatePubSubType>(dds::kMotionTopic, dds::TopicClass::Chain));
      segs.push_back(participant.make_writer<msg::SegmentationPubSubType>(dds::kSegmentationTopic, dds::TopicClass::Chain));
      tracks.push_back(participant.make_writer<msg::TrackListPubSubType>(dds::kTracksTopic, dds::TopicClass::Chain));
    }
  }
  static dds::DdsOptions options(int domain) {
    dds::DdsOptions o;
    o.domain_id = domain;
    o.participant_name = "rogue";
    return o;
  }
  void flood() {
    // Only the sink runs yet: one reader each.
    for (size_t w = 0; w < motions.size(); ++w) {
      ASSERT_TRUE(motions[w]->wait_for_matched(1, std::chrono::seconds(30)));
      ASSERT_TRUE(segs[w]->wait_for_matched(1, std::chrono::seconds(30)));
      ASSERT_TRUE(tracks[w]->wait_for_matched(1, std::chrono::seconds(30)));
    }
    for (int i = 0; i < kForgedIds; ++i) {
      const size_t w = static_cast<size_t>(i / 10);
      const std::string id = "forged" + std::to_string(i);
      MotionEstimate m;
      m.stream_id = id;
      m.frame_index = 1;
      m.image_width = 640;
      m.image_height = 480;
      auto mm = dds::to_msg(m);
      ASSERT_TRUE(motions[w]->write_reliably(mm)) << id;
      SegmentationResult s;
      s.stream_id = id;
      s.frame_index = 1;
      auto sm = dds::to_msg(s);
      ASSERT_TRUE(segs[w]->write_reliably(sm)) << id;
      TrackList t;
      t.stream_id = id;
      t.frame_index = 1;
      auto tm = dds::to_msg(t);
      ASSERT_TRUE(tracks[w]->write_reliably(tm)) << id;
    }
  }
  dds::Participant participant;
  std::vector<std::unique_ptr<dds::TopicWriter<msg::MotionEstimatePubSubType>>> motions;
  std::vector<std::unique_ptr<dds::TopicWriter<msg::SegmentationPubSubType>>> segs;
  std::vector<std::unique_ptr<dds::TopicWriter<msg::TrackListPubSubType>>> tracks;
};

// The chain of bringup/local.yaml, one process each, with the sink started (and flooded, when
// ROGUE is given) before the others. Returns the sink's exit code (nullopt: still running after
// the deadline).
std::optional<int> run_chain(const std::string& sequence, const std::string& dir, int domain, Rogue* rogue) {
  std::filesystem::create_directories(dir);
  const std::vector<std::string> common = {"--domain", std::to_string(domain), "--mode", "lossless"};
  const std::string config = std::string(UAVMOT_SOURCE_DIR) + "/bringup/chain.yaml";
  const std::vector<std::string> algo = {"--config", config, "--gsd", seqinfo(sequence, "gsd"), "--fps", seqinfo(sequence, "frameRate")};
  auto args = [&](std::vector<std::string> a, bool with_algo = true) {
    if (with_algo) a.insert(a.end(), algo.begin(), algo.end());
    a.insert(a.end(), common.begin(), common.end());
    return a;
  };
  ChildProcess sink(args({binary("uavmot-sink"), "--out", dir + "/results", "--stream-id", "uav1", "--gsd", seqinfo(sequence, "gsd"),
                         "--fps", seqinfo(sequence, "frameRate")},
                        false),
                    dir + "/sink.log");
  if (rogue) {
    rogue->flood();
    if (::testing::Test::HasFatalFailure()) return std::nullopt;
  }
  ChildProcess tracking(args({binary("uavmot-tracking"), "--wait-subscribers", "1"}), dir + "/tracking.log");
  ChildProcess segmentation(args({binary("uavmot-segmentation"), "--wait-subscribers", "2"}), dir + "/segmentation.log");
  ChildProcess motion(args({binary("uavmot-motion"), "--wait-subscribers", "3"}), dir + "/motion.log");
  ChildProcess source(args({binary("uavmot-source"), sequence, "--stream-id", "uav1", "--wait-subscribers", "2"}, false),
                      dir + "/source.log");
  for (auto* p : {&source, &motion, &segmentation, &tracking}) {
    EXPECT_EQ(p->wait(std::chrono::seconds(120)), 0) << p->log();
  }
  const auto code = sink.wait(std::chrono::seconds(30));
  EXPECT_EQ(code, 0) << sink.log();
  return code;
}

TEST(SinkInstanceFlood, ForgedStreamIdsBeforeTheChainDoNotCrowdOutTheExpectedStream) {
  const std::string root = testing::fresh_dir("sink_instance_flood");
  const std::string sequence = root + "/sequence";
  ChildProcess sim({binary("uavmot-sim"), "--preset", "paper", "--seed", "3", "--frames", "40", "--out", sequence},
                   root + "/sim.log");
  ASSERT_EQ(sim.wait(std::chrono::seconds(120)), 0) << sim.log();

  ASSERT_EQ(run_chain(sequence, root + "/undisturbed", 191, nullptr), 0);
  Rogue rogue(192);
  ASSERT_EQ(run_chain(sequence, root + "/flooded", 192, &rogue), 0);

  const std::string expected = testing::read_file(root + "/undisturbed/results/tracks.txt");
  EXPECT_FALSE(expected.empty()) << "the undisturbed run has tracks to compare";
  for (const char* file : {"tracks.txt", "tracks_obb.csv", "homographies.txt", "regions.txt"}) {
    EXPECT_EQ(testing::read_file(root + "/flooded/results/" + file), testing::read_file(root + "/undisturbed/results/" + file))
        << file;
  }
  const std::string homographies = testing::read_file(root + "/flooded/results/homographies.txt");
  EXPECT_EQ(std::count(homographies.begin(), homographies.end(), '\n'), 40) << "every frame";
}

}  // namespace
}  // namespace uavmot
