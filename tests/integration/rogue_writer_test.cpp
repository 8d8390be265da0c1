// A rogue writer publishes malformed samples on every chain topic: wrong sizes, NaN, oversized
// sequences. No component may crash; each counts what it rejected on uavmot/health and keeps
// processing the valid stream that follows.

#include <cmath>
#include <map>
#include <thread>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "child_process.hpp"
#include "framePubSubTypes.h"
#include "healthPubSubTypes.h"
#include "motionPubSubTypes.h"
#include "segmentationPubSubTypes.h"
#include "tracksPubSubTypes.h"
#include "uavmot/build_paths/build_paths.hpp"
#include "uavmot/dds/chain_convert.hpp"
#include "uavmot/dds/frame_convert.hpp"
#include "uavmot/dds/participant.hpp"

namespace uavmot {
namespace {
using testing::binary;
using testing::ChildProcess;

constexpr int kDomain = 71;

dds::DdsOptions rogue_options() {
  dds::DdsOptions o;
  o.domain_id = kDomain;
  o.participant_name = "rogue";
  return o;
}

TEST(RogueWriter, MalformedSamplesAreCountedAndDroppedWhileTheChainGoesOn) {
  const std::string out = testing::fresh_dir("rogue_writer");
  const std::vector<std::string> common = {"--domain", std::to_string(kDomain), "--mode", "lossless"};
  auto args = [&](std::vector<std::string> a) {
    a.insert(a.end(), common.begin(), common.end());
    return a;
  };
  ChildProcess sink(args({binary("uavmot-sink"), "--out", out + "/results"}), out + "/sink.log");
  // Each writer waits for its readers (as bringup/local.yaml has it): on a busy host discovery can
  // take longer than the rogue's writes, and an unmatched reader would miss the valid results.
  ChildProcess tracking(args({binary("uavmot-tracking"), "--wait-subscribers", "1"}), out + "/tracking.log");
  ChildProcess segmentation(args({binary("uavmot-segmentation"), "--wait-subscribers", "2"}), out + "/segmentation.log");
  ChildProcess motion(args({binary("uavmot-motion"), "--wait-subscribers", "3"}), out + "/motion.log");

  dds::Participant rogue(rogue_options());
  auto frames = rogue.make_writer<msg::FramePubSubType>(dds::kFramesTopic, dds::TopicClass::Frames);
  auto motions = rogue.make_writer<msg::MotionEstimatePubSubType>(dds::kMotionTopic, dds::TopicClass::Chain);
  auto segs = rogue.make_writer<msg::SegmentationPubSubType>(dds::kSegmentationTopic, dds::TopicClass::Chain);
  auto tracks = rogue.make_writer<msg::TrackListPubSubType>(dds::kTracksTopic, dds::TopicClass::Chain);
  auto health = rogue.make_reader<msg::ComponentHealthPubSubType>(dds::kHealthTopic, dds::TopicClass::Health);
  ASSERT_TRUE(frames->wait_for_matched(2, std::chrono::seconds(30)));   // motion, segmentation
  ASSERT_TRUE(motions->wait_for_matched(3, std::chrono::seconds(30)));  // segmentation, tracking, sink
  ASSERT_TRUE(segs->wait_for_matched(2, std::chrono::seconds(30)));     // tracking, sink
  ASSERT_TRUE(tracks->wait_for_matched(1, std::chrono::seconds(30)));   // sink

  // Garbage, on every topic.
  cv::Mat image = cv::imread(build_paths::data_dir() + "/clif2007/jpg/000000-100006.jpg", cv::IMREAD_GRAYSCALE);
  ASSERT_FALSE(image.empty());
  cv::resize(image, image, {320, 480});
  auto frame_sample = dds::to_msg(Frame{"uav1", 1, 0, image});
  frame_sample.data().resize(1000);  // payload does not match width x height
  ASSERT_TRUE(frames->write_reliably(frame_sample));
  frame_sample = dds::to_msg(Frame{"uav1", 1, 0, image});
  frame_sample.width(0);
  ASSERT_TRUE(frames->write_reliably(frame_sample));

  MotionEstimate bad_motion;
  bad_motion.stream_id = "uav1";
  bad_motion.frame_index = 1;
  auto motion_sample = dds::to_msg(bad_motion);
  motion_sample.homography()[0] = NAN;
  ASSERT_TRUE(motions->write_reliably(motion_sample));
  motion_sample = dds::to_msg(bad_motion);
  motion_sample.features().resize(dds::kMaxFeatures + 10);  // oversized sequence
  ASSERT_TRUE(motions->write_reliably(motion_sample));

  SegmentationResult bad_seg;
  bad_seg.stream_id = "uav1";
  bad_seg.frame_index = 1;
  bad_seg.regions = {{{10, 10, -4, 12, 0}, SegmentationMethod::Fusion, 1.0, -1}};
  auto seg_sample = dds::to_msg(bad_seg);
  ASSERT_TRUE(segs->write_reliably(seg_sample));

  TrackList bad_tracks;
  bad_tracks.stream_id = "uav1";
  bad_tracks.frame_index = 1;
  Track nan_track;
  nan_track.id = 1;
  nan_track.box = {NAN, 1, 1, 1, 0};
  bad_tracks.tracks = {nan_track};
  auto tracks_sample = dds::to_msg(bad_tracks);
  ASSERT_TRUE(tracks->write_reliably(tracks_sample));

  // Then a valid stream of 8 frames and its end.
  for (int i = 1; i <= 8; ++i) {
    cv::Mat shifted;
    cv::warpAffine(image, shifted, cv::Mat(cv::Matx23d(1, 0, i * 0.7, 0, 1, i * 0.3)), image.size(), cv::INTER_LINEAR,
                   cv::BORDER_REFLECT);
    auto sample = dds::to_msg(Frame{"uav1", i, i * 40'000'000LL, shifted});
    ASSERT_TRUE(frames->write_reliably(sample));
  }
  auto eos = dds::end_of_stream_frame("uav1", 8);
  ASSERT_TRUE(frames->write_reliably(eos));
  ASSERT_TRUE(frames->flush());

  // Everyone finishes cleanly: nothing crashed.
  for (auto* p : {&motion, &segmentation, &tracking, &sink}) {
    EXPECT_EQ(p->wait(std::chrono::seconds(60)), 0) << p->log();
  }
  // Each component counted the garbage it received on its health topic.
  std::map<std::string, uint64_t> invalid;
  msg::ComponentHealth report;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (std::chrono::steady_clock::now() < deadline && invalid.size() < 4) {
    while (health->take(report)) {
      auto& n = invalid[report.component_name().to_string()];
      n = std::max<uint64_t>(n, report.invalid_samples());
    }
    health->wait_for_data(std::chrono::milliseconds(200));
  }
  EXPECT_EQ(invalid["motion"], 2u) << "two malformed frames";
  EXPECT_EQ(invalid["segmentation"], 4u) << "two malformed frames and two malformed motion estimates";
  EXPECT_EQ(invalid["tracking"], 3u) << "two malformed motion estimates and one malformed segmentation";
  EXPECT_EQ(invalid["sink"], 4u) << "motion x2, segmentation, tracks";
  // Logged with their cause.
  EXPECT_NE(motion.log().find("dropped a malformed sample"), std::string::npos) << motion.log();
  // The valid stream went through the whole chain.
  const std::string homographies = testing::read_file(out + "/results/homographies.txt");
  EXPECT_EQ(std::count(homographies.begin(), homographies.end(), '\n'), 8);
}

}  // namespace
}  // namespace uavmot
