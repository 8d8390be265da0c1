// Stream ids come from the wire and name the sink's folders and preview files. A participant on the
// sink's domain (as anyone on the network could be) sends samples and ends of stream with ids
// that climb out of the output folder ("../../etc", "..", an absolute path), an overlong id and
// ids of streams the run was not started for. The sink writes nothing for them (nothing outside
// its folders, no truncated results), keeps the real stream's results whole, ends only when the
// real stream ends, and logs and counts every refusal.

#include <algorithm>
#include <filesystem>
#include <set>
#include <thread>

#include <gtest/gtest.h>

#include "chain_samples.hpp"
#include "child_process.hpp"
#include "downlinkPubSubTypes.h"
#include "framePubSubTypes.h"
#include "motionPubSubTypes.h"
#include "segmentationPubSubTypes.h"
#include "tracksPubSubTypes.h"
#include "uavmot/dds/chain_convert.hpp"
#include "uavmot/dds/downlink_convert.hpp"
#include "uavmot/dds/participant.hpp"

namespace uavmot {
namespace {
namespace fs = std::filesystem;
using testing::binary;
using testing::ChildProcess;

const std::string kAbsolute = "/tmp/uavmot_stream_ids_test_x";
// Ids that are no safe folder name.
const std::vector<std::string> kUnsafe = {"../../etc", kAbsolute, "..", ".", "a/b"};
// The IDL's string<64> (a fixed_string<64>) cuts an overlong id to its first 64 characters on the
// wire, so it arrives as a valid id of a stream the run was not started for.
const std::string kOverlong(200, 'L');
// How the sink's log shows each refused id.
std::vector<std::string> shown(const std::vector<std::string>& more) {
  std::vector<std::string> out = {"'../../etc'", "'" + kAbsolute + "'", "'..'", "'.'", "'a/b'", "'" + std::string(64, 'L') + "'"};
  for (const auto& id : more) out.push_back("'" + id + "'");
  return out;
}

dds::DdsOptions options(int domain) {
  dds::DdsOptions o;
  o.domain_id = domain;
  o.participant_name = "forger";
  return o;
}

// One confirmed track per frame, its id telling the streams apart.
TrackList tracks(const std::string& stream, int64_t k) {
  TrackList t = testing::tracks_of(stream, k);
  Track track;
  track.id = stream == "uav1" ? 1 : 99;
  track.state = TrackState::Confirmed;
  track.box = {100.0 + static_cast<double>(k), 50, 2, 10, 0};
  track.velocity = {1.0, 0.0};
  t.tracks = {track};
  return t;
}

// Entries under DIR, relative, recursively.
std::set<std::string> tree(const fs::path& dir) {
  std::set<std::string> names;
  for (const auto& e : fs::recursive_directory_iterator(dir)) names.insert(fs::relative(e.path(), dir).string());
  return names;
}

// Where a sink that trusted stream ids would write: beside OUT (its folder in the test's ROOT,
// which holds only the cases' folders and logs), and the absolute id.
void expect_nothing_outside(const fs::path& root) {
  EXPECT_FALSE(fs::exists(kAbsolute)) << kAbsolute;
  for (const auto& e : fs::directory_iterator(root)) {
    const std::string name = e.path().filename().string();
    EXPECT_TRUE((e.is_directory() && (name == "downlink" || name == "chain")) || e.path().extension() == ".log") << e.path();
  }
}

void expect_tracks_of_frames(const std::string& file, int frames, int64_t id) {
  const std::string text = testing::read_file(file);
  std::string expected;
  for (int k = 1; k <= frames; ++k) {
    // The box (cx 100 + k, cy 50, 2 across, 10 along the x axis) as MOTChallenge bounds.
    expected += std::to_string(k) + "," + std::to_string(id) + "," + std::to_string(95 + k) + ".000,49.000,10.000,2.000,1.000,-1,-1,-1\n";
  }
  EXPECT_EQ(text, expected) << file;
}

class SinkStreamIds : public ::testing::Test {
 protected:
  void SetUp() override {
    fs::remove_all(kAbsolute);
    root_ = testing::fresh_dir("sink_stream_ids");
    fs::remove_all(fs::path(root_).parent_path() / "etc");
  }
  std::string root_;
};

// The link's sink (--streams 1): the first valid id binds the run; previews are saved for it only.
TEST_F(SinkStreamIds, DownlinkSinkWritesOnlyTheBoundStream) {
  constexpr int kDomain = 77;
  const fs::path out = fs::path(root_) / "downlink";
  fs::create_directories(out);
  ChildProcess sink({binary("uavmot-sink"), "--downlink", "--out", (out / "results").string(), "--preview-dir",
                     (out / "previews").string(), "--domain", std::to_string(kDomain), "--mode", "lossless"},
                    root_ + "/downlink_sink.log");
  dds::Participant forger(options(kDomain));
  auto results = forger.make_writer<msg::FrameResultsPubSubType>(dds::kDownlinkResultsTopic, dds::TopicClass::Downlink);
  auto previews = forger.make_writer<msg::FramePubSubType>(dds::kDownlinkPreviewTopic, dds::TopicClass::Preview);
  ASSERT_TRUE(results->wait_for_matched(1, std::chrono::seconds(30)));
  ASSERT_TRUE(previews->wait_for_matched(1, std::chrono::seconds(30)));

  auto result = [&](const std::string& stream, int64_t k) {
    dds::FrameParts parts;
    parts.motion = testing::motion_of(stream, k);
    parts.tracks = tracks(stream, k);
    auto sample = dds::to_downlink_msg(stream, k, parts);
    ASSERT_TRUE(results->write_reliably(sample)) << stream;
  };
  auto end = [&](const std::string& stream) {
    msg::FrameResults eos;
    eos.stream_id(stream);
    eos.frame_index(8);
    eos.end_of_stream(true);
    ASSERT_TRUE(results->write_reliably(eos)) << stream;
  };
  auto preview = [&](const std::string& stream, int64_t k) {
    msg::Frame jpeg;
    jpeg.stream_id(stream);
    jpeg.frame_index(k);
    jpeg.encoding(msg::Encoding::JPEG);
    jpeg.data(std::vector<uint8_t>{0xFF, 0xD8, 0xFF, 0xD9});
    previews->write(jpeg);
    std::this_thread::sleep_for(std::chrono::milliseconds(20));  // best effort: give each its turn
  };

  for (int k = 1; k <= 4; ++k) {
    result("uav1", k);
    preview("uav1", k);
  }
  std::vector<std::string> forged = kUnsafe;
  forged.push_back(kOverlong);
  forged.push_back("uav2");
  for (const auto& id : forged) {
    for (int k = 1; k <= 3; ++k) {
      result(id, k);
      preview(id, k);
    }
    end(id);  // must end nothing
  }
  for (int k = 5; k <= 8; ++k) {
    result("uav1", k);
    preview("uav1", k);
  }
  // Still running: none of the forged ends ended the run.
  EXPECT_FALSE(sink.wait(std::chrono::milliseconds(500)).has_value()) << sink.log();
  end("uav1");
  ASSERT_EQ(sink.wait(std::chrono::seconds(60)), 0) << sink.log();

  expect_tracks_of_frames((out / "results/tracks.txt").string(), 8, 1);
  const std::string homographies = testing::read_file((out / "results/homographies.txt").string());
  EXPECT_EQ(std::count(homographies.begin(), homographies.end(), '\n'), 8) << homographies;
  EXPECT_FALSE(tree(out / "previews").empty()) << "the real stream's previews are saved";
  for (const auto& name : tree(out)) {
    EXPECT_TRUE(name == "results" || name == "previews" || name.rfind("results/", 0) == 0 || name.rfind("previews/uav1_", 0) == 0)
        << name;
  }
  expect_nothing_outside(root_);
  const std::string log = sink.log();
  EXPECT_NE(log.find("stream 'uav1' bound"), std::string::npos) << log;
  for (const auto& id : shown({"uav2"})) {
    EXPECT_NE(log.find("stream " + id + ": "), std::string::npos) << "the summary names " << id << "\n" << log;
  }
  EXPECT_NE(log.find("refused"), std::string::npos) << log;
}

// The chain's sink with --streams 2: each valid id gets its own folder, up to two; a third id and
// every unsafe id get none.
TEST_F(SinkStreamIds, ChainSinkGivesTwoValidIdsAFolderEachAndNothingElse) {
  constexpr int kDomain = 78;
  const fs::path out = fs::path(root_) / "chain";
  fs::create_directories(out);
  ChildProcess sink({binary("uavmot-sink"), "--streams", "2", "--out", (out / "results").string(), "--domain",
                     std::to_string(kDomain), "--mode", "lossless"},
                    root_ + "/chain_sink.log");
  dds::Participant forger(options(kDomain));
  auto motions = forger.make_writer<msg::MotionEstimatePubSubType>(dds::kMotionTopic, dds::TopicClass::Chain);
  auto segs = forger.make_writer<msg::SegmentationPubSubType>(dds::kSegmentationTopic, dds::TopicClass::Chain);
  auto track_lists = forger.make_writer<msg::TrackListPubSubType>(dds::kTracksTopic, dds::TopicClass::Chain);
  ASSERT_TRUE(motions->wait_for_matched(1, std::chrono::seconds(30)));
  ASSERT_TRUE(segs->wait_for_matched(1, std::chrono::seconds(30)));
  ASSERT_TRUE(track_lists->wait_for_matched(1, std::chrono::seconds(30)));

  auto frame = [&](const std::string& stream, int64_t k) {
    auto m = dds::to_msg(testing::motion_of(stream, k));
    ASSERT_TRUE(motions->write_reliably(m));
    SegmentationResult s;
    s.stream_id = stream;
    s.frame_index = k;
    auto sm = dds::to_msg(s);
    ASSERT_TRUE(segs->write_reliably(sm));
    auto tm = dds::to_msg(tracks(stream, k));
    ASSERT_TRUE(track_lists->write_reliably(tm));
  };
  auto end = [&](const std::string& stream) {
    auto m = dds::to_msg(testing::motion_of(stream, 8));
    m.end_of_stream(true);
    ASSERT_TRUE(motions->write_reliably(m));
    SegmentationResult s;
    s.stream_id = stream;
    s.frame_index = 8;
    auto sm = dds::to_msg(s);
    sm.end_of_stream(true);
    ASSERT_TRUE(segs->write_reliably(sm));
    auto tm = dds::to_msg(tracks(stream, 8));
    tm.end_of_stream(true);
    ASSERT_TRUE(track_lists->write_reliably(tm));
  };

  for (int k = 1; k <= 4; ++k) frame("uav1", k);
  for (int k = 1; k <= 3; ++k) frame("uav2", k);  // valid: binds the second folder
  std::vector<std::string> forged = kUnsafe;
  // A valid id, but no room for a third. (The overlong id is the downlink case's: the sink's
  // readers keep 8 instances, bringup/qos/uavmot_qos.xml, and uav1, uav2 and these are 8.)
  forged.push_back("uav3");
  for (const auto& id : forged) {
    for (int k = 1; k <= 3; ++k) frame(id, k);
    end(id);
  }
  for (int k = 5; k <= 8; ++k) frame("uav1", k);
  end("uav1");
  EXPECT_FALSE(sink.wait(std::chrono::milliseconds(500)).has_value()) << "uav2 has not ended\n" << sink.log();
  end("uav2");
  ASSERT_EQ(sink.wait(std::chrono::seconds(60)), 0) << sink.log();

  expect_tracks_of_frames((out / "results/uav1/tracks.txt").string(), 8, 1);
  expect_tracks_of_frames((out / "results/uav2/tracks.txt").string(), 3, 99);
  std::set<std::string> top;
  for (const auto& e : fs::directory_iterator(out / "results")) top.insert(e.path().filename().string());
  EXPECT_EQ(top, (std::set<std::string>{"uav1", "uav2"}));
  EXPECT_EQ(tree(out).size(), tree(out / "results").size() + 1) << "only results/ under the output folder";
  expect_nothing_outside(root_);
  const std::string log = sink.log();
  std::vector<std::string> refused = shown({"uav3"});
  refused.erase(std::find(refused.begin(), refused.end(), "'" + std::string(64, 'L') + "'"));
  for (const auto& id : refused) {
    EXPECT_NE(log.find("stream " + id + ": "), std::string::npos) << "the summary names " << id << "\n" << log;
  }
}

}  // namespace
}  // namespace uavmot
