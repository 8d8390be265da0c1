// Instance floods: a rogue participant publishes samples of 20 made-up stream ids before the real
// stream. A reader keeps at most 8 stream ids (max_instances); Fast DDS 2.9 never evicts an alive
// one, so without a filter the real stream's samples are rejected by DDS before any stream gate
// sees them, and the run never ends. With a stream id to expect, the readers filter on the key (a
// ContentFilteredTopic, evaluated before a sample enters the history) and the run is undisturbed:
// - the chain's sink (bringup/local.yaml: --stream-id);
// - the ground (bringup/ground.yaml: its sink's --stream-id from stream_ids), flooded on the link;
// - the downlink (bringup/air.yaml: --stream-id), flooded on the UAV's own domain, where forged
//   ends of stream would otherwise also end its run before the real stream went down.

#include <signal.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <vector>

#include <gtest/gtest.h>

#include "chain_samples.hpp"
#include "child_process.hpp"
#include "downlinkPubSubTypes.h"
#include "motionPubSubTypes.h"
#include "segmentationPubSubTypes.h"
#include "tracksPubSubTypes.h"
#include "uavmot/build_paths/build_paths.hpp"
#include "uavmot/dds/chain_convert.hpp"
#include "uavmot/dds/downlink_convert.hpp"
#include "uavmot/dds/node_support.hpp"
#include "uavmot/dds/participant.hpp"

namespace uavmot {
namespace {
using testing::binary;
using testing::motion_of;
using testing::segmentation_of;
using testing::tracks_of;
using testing::ChildProcess;

constexpr int kForgedIds = 20;
constexpr int kIdsPerWriter = 10;  // a writer holds at most 10 instances (Fast DDS's default max_instances)

std::string forged_id(int i) { return "forged" + std::to_string(i); }

// PROFILE: "local" (the chain's on one host), "shm" (the UAV's own domain), "udp" (a link's).
dds::DdsOptions rogue_options(int domain, const std::string& profile = "local") {
  dds::DdsOptions o;
  o.domain_id = domain;
  o.participant_name = "rogue";
  o.participant_profile = profile;
  return o;
}

// Enough writers on TOPIC for every forged id, each matched to the one reader that runs yet.
template <class PubSubType>
std::vector<std::unique_ptr<dds::TopicWriter<PubSubType>>> forged_writers(dds::Participant& p, const std::string& topic,
                                                                          dds::TopicClass topic_class) {
  std::vector<std::unique_ptr<dds::TopicWriter<PubSubType>>> writers;
  for (int i = 0; i < kForgedIds; i += kIdsPerWriter) {
    writers.push_back(p.make_writer<PubSubType>(topic, topic_class));
    EXPECT_TRUE(writers.back()->wait_for_matched(1, std::chrono::seconds(30))) << topic;
  }
  return writers;
}

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
  explicit Rogue(int domain) : participant(rogue_options(domain)) {
    for (int i = 0; i < kForgedIds; i += kIdsPerWriter) {
      motions.push_back(participant.make_writer<msg::MotionEstimatePubSubType>(dds::kMotionTopic, dds::TopicClass::Chain));
      segs.push_back(participant.make_writer<msg::SegmentationPubSubType>(dds::kSegmentationTopic, dds::TopicClass::Chain));
      tracks.push_back(participant.make_writer<msg::TrackListPubSubType>(dds::kTracksTopic, dds::TopicClass::Chain));
    }
  }
  void flood() {
    // Only the sink runs yet: one reader each.
    for (size_t w = 0; w < motions.size(); ++w) {
      ASSERT_TRUE(motions[w]->wait_for_matched(1, std::chrono::seconds(30)));
      ASSERT_TRUE(segs[w]->wait_for_matched(1, std::chrono::seconds(30)));
      ASSERT_TRUE(tracks[w]->wait_for_matched(1, std::chrono::seconds(30)));
    }
    for (int i = 0; i < kForgedIds; ++i) {
      const size_t w = static_cast<size_t>(i / kIdsPerWriter);
      const std::string id = forged_id(i);
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
  const std::string config = build_paths::source_dir() + "/bringup/chain.yaml";
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

  ASSERT_EQ(run_chain(sequence, root + "/undisturbed", 160, nullptr), 0);
  Rogue rogue(161);
  ASSERT_EQ(run_chain(sequence, root + "/flooded", 161, &rogue), 0);

  const std::string expected = testing::read_file(root + "/undisturbed/results/tracks.txt");
  EXPECT_FALSE(expected.empty()) << "the undisturbed run has tracks to compare";
  for (const char* file : {"tracks.txt", "tracks_obb.csv", "homographies.txt", "regions.txt"}) {
    EXPECT_EQ(testing::read_file(root + "/flooded/results/" + file), testing::read_file(root + "/undisturbed/results/" + file))
        << file;
  }
  const std::string homographies = testing::read_file(root + "/flooded/results/homographies.txt");
  EXPECT_EQ(std::count(homographies.begin(), homographies.end(), '\n'), 40) << "every frame";
}

constexpr int kRealFrames = 8;

size_t lines_of(const std::string& file) {
  const std::string text = testing::read_file(file);
  return static_cast<size_t>(std::count(text.begin(), text.end(), '\n'));
}

// bringup/ground.yaml as shipped (stream_ids uav1), its link flooded by 20 forged ids before uav1's
// 8 frames and end of stream come from a writer of their own (as the UAV's downlink): all 8 are
// written and the launch ends by itself. Without the filter the sink's reader is full of forged ids
// (and its first-come gate would take forged0 for the stream): it never ends.
TEST(SinkInstanceFlood, GroundProfileFiltersForgedIdsOnTheLink) {
  constexpr int kDomain = 162;
  const std::string root = testing::fresh_dir("sink_instance_flood_ground");
  ChildProcess ground({binary("uavmot"), "launch", build_paths::source_dir() + "/bringup/ground.yaml", "--out",
                       root + "/results", "--set", "domain=" + std::to_string(kDomain), "--set", "gsd=0.35", "--set", "fps=25"},
                      root + "/ground.log");
  dds::Participant rogue(rogue_options(kDomain, "udp"));
  auto forged = forged_writers<msg::FrameResultsPubSubType>(rogue, dds::kDownlinkResultsTopic, dds::TopicClass::Downlink);
  ASSERT_FALSE(::testing::Test::HasFailure()) << ground.log();
  auto send = [&](dds::TopicWriter<msg::FrameResultsPubSubType>& writer, const std::string& stream, int64_t k) {
    dds::FrameParts parts;
    parts.motion = motion_of(stream, k);
    parts.segmentation = segmentation_of(stream, k);
    parts.tracks = tracks_of(stream, k);
    auto sample = dds::to_downlink_msg(stream, k, parts);
    EXPECT_TRUE(writer.write_reliably(sample)) << stream << " " << k;
  };
  for (int i = 0; i < kForgedIds; ++i) send(*forged[static_cast<size_t>(i / kIdsPerWriter)], forged_id(i), 1);
  auto uav = rogue.make_writer<msg::FrameResultsPubSubType>(dds::kDownlinkResultsTopic, dds::TopicClass::Downlink);
  ASSERT_TRUE(uav->wait_for_matched(1, std::chrono::seconds(30)));
  for (int k = 1; k <= kRealFrames; ++k) send(*uav, "uav1", k);
  dds::write_end_of_stream(*uav, "uav1", kRealFrames, dds::DeliveryMode::Lossless);
  const auto code = ground.wait(std::chrono::seconds(60));
  if (!code) {  // the launcher stops its sink
    ground.signal(SIGINT);
    ground.wait(std::chrono::seconds(30));
  }
  ASSERT_EQ(code, 0) << ground.log();
  EXPECT_EQ(lines_of(root + "/results/homographies.txt"), static_cast<size_t>(kRealFrames)) << ground.log();
  EXPECT_EQ(ground.log().find("forged"), std::string::npos) << "no forged id reached the sink\n" << ground.log();
}

// uavmot-downlink as bringup/air.yaml runs it (--stream-id uav1), with a ground sink: 20 forged ids
// on the UAV's own domain, each with its end of stream, before uav1's 8 frames and end. Every frame
// of uav1 reaches the ground, and the downlink ends with uav1's end. Without the filter its readers
// are full of forged ids, and forged0's end of stream ends its run (--streams 1) first.
TEST(SinkInstanceFlood, DownlinkFiltersForgedIdsOnTheAirDomain) {
  constexpr int kLinkDomain = 163, kAirDomain = 164;
  const std::string root = testing::fresh_dir("sink_instance_flood_downlink");
  ChildProcess sink({binary("uavmot-sink"), "--downlink", "--stream-id", "uav1", "--out", root + "/results", "--domain",
                     std::to_string(kLinkDomain), "--transport", "udp", "--mode", "lossless"},
                    root + "/sink.log");
  ChildProcess downlink({binary("uavmot-downlink"), "--domain", std::to_string(kLinkDomain), "--transport", "udp", "--air-domain",
                         std::to_string(kAirDomain), "--air-transport", "shm", "--stream-id", "uav1", "--wait-subscribers", "1",
                         "--mode", "lossless"},
                        root + "/downlink.log");
  dds::Participant rogue(rogue_options(kAirDomain, "shm"));  // as the UAV's chain (air.yaml)
  auto motions = forged_writers<msg::MotionEstimatePubSubType>(rogue, dds::kMotionTopic, dds::TopicClass::Chain);
  auto segs = forged_writers<msg::SegmentationPubSubType>(rogue, dds::kSegmentationTopic, dds::TopicClass::Chain);
  auto tracks = forged_writers<msg::TrackListPubSubType>(rogue, dds::kTracksTopic, dds::TopicClass::Chain);
  ASSERT_FALSE(::testing::Test::HasFailure()) << downlink.log();
  // Frame K of STREAM on writer W of each topic, or (K = 0) its end of stream at frame LAST.
  auto send = [&](size_t w, const std::string& stream, int64_t k) {
    auto m = dds::to_msg(motion_of(stream, k));
    auto s = dds::to_msg(segmentation_of(stream, k));
    auto t = dds::to_msg(tracks_of(stream, k));
    EXPECT_TRUE(motions[w]->write_reliably(m) && segs[w]->write_reliably(s) && tracks[w]->write_reliably(t)) << stream << " " << k;
  };
  auto end = [&](size_t w, const std::string& stream, int64_t last) {
    dds::write_end_of_stream(*motions[w], stream, last, dds::DeliveryMode::Lossless);
    dds::write_end_of_stream(*segs[w], stream, last, dds::DeliveryMode::Lossless);
    dds::write_end_of_stream(*tracks[w], stream, last, dds::DeliveryMode::Lossless);
  };
  for (int i = 0; i < kForgedIds; ++i) {
    send(static_cast<size_t>(i / kIdsPerWriter), forged_id(i), 1);
    end(static_cast<size_t>(i / kIdsPerWriter), forged_id(i), 1);
  }
  // uav1 from writers of their own (as the UAV's chain): the forged ones hold 10 instances each.
  motions.push_back(rogue.make_writer<msg::MotionEstimatePubSubType>(dds::kMotionTopic, dds::TopicClass::Chain));
  segs.push_back(rogue.make_writer<msg::SegmentationPubSubType>(dds::kSegmentationTopic, dds::TopicClass::Chain));
  tracks.push_back(rogue.make_writer<msg::TrackListPubSubType>(dds::kTracksTopic, dds::TopicClass::Chain));
  const size_t real = motions.size() - 1;
  ASSERT_TRUE(motions[real]->wait_for_matched(1, std::chrono::seconds(30)) && segs[real]->wait_for_matched(1, std::chrono::seconds(30)) &&
              tracks[real]->wait_for_matched(1, std::chrono::seconds(30)))
      << downlink.log();
  for (int k = 1; k <= kRealFrames; ++k) send(real, "uav1", k);
  end(real, "uav1", kRealFrames);
  const auto downlink_code = downlink.wait(std::chrono::seconds(60));
  const auto sink_code = sink.wait(std::chrono::seconds(30));
  EXPECT_EQ(downlink_code, 0) << downlink.log();
  ASSERT_EQ(sink_code, 0) << sink.log() << downlink.log();
  EXPECT_EQ(lines_of(root + "/results/homographies.txt"), static_cast<size_t>(kRealFrames)) << sink.log();
  EXPECT_NE(downlink.log().find("stream 'uav1' ended"), std::string::npos) << downlink.log();
  EXPECT_EQ(downlink.log().find("forged"), std::string::npos) << "no forged id reached the downlink\n" << downlink.log();
}

}  // namespace
}  // namespace uavmot
