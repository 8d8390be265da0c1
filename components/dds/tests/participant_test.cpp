#include "uavmot/dds/participant.hpp"

#include <thread>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "framePubSubTypes.h"
#include "test_participants.hpp"
#include "tracksPubSubTypes.h"
#include "uavmot/core/checksum.hpp"
#include "uavmot/core/error.hpp"
#include "uavmot/dds/frame_convert.hpp"

namespace uavmot::dds {
namespace {

// A domain of its own so parallel test runs do not see each other.
constexpr int kDomain = 91;

DdsOptions options(const std::string& name, const std::string& profiles_file = "", const std::string& profile = "local") {
  return test_support::options_on(kDomain, name, profiles_file, profile);
}

// The frame indices `reader` takes into `sample` until it holds `count` of them (or 10 s pass).
template <class Reader, class Sample>
std::vector<int64_t> indices_taken(Reader& reader, Sample& sample, size_t count) {
  std::vector<int64_t> indices;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (indices.size() < count && std::chrono::steady_clock::now() < deadline) {
    reader.wait_for_data(std::chrono::milliseconds(100));
    while (reader.take(sample)) indices.push_back(sample.frame_index());
  }
  return indices;
}

TEST(Participant, MissingProfilesOrProfileNamesAreInputErrors) {
  EXPECT_THROW(Participant(options("x", "/nonexistent.xml")), InputError);
  EXPECT_THROW(Participant(options("x", "", "no_such_profile")), InputError);
}

TEST(Participant, LosslessFramesArriveWholeOverSharedMemory) {
  Participant publisher_side(options("pub"));
  Participant subscriber_side(options("sub"));
  auto writer = publisher_side.make_writer<msg::FramePubSubType>(kFramesTopic, TopicClass::Frames);
  auto reader = subscriber_side.make_reader<msg::FramePubSubType>(kFramesTopic, TopicClass::Frames);
  ASSERT_TRUE(writer->wait_for_matched(1, std::chrono::seconds(10)));

  // 1080p mono8 frames (2 MB): more than the reader's queue of 4, so backpressure is exercised.
  constexpr int kFrames = 12;
  std::vector<uint64_t> sent;
  cv::RNG rng(7);
  std::thread produce([&] {
    for (int i = 1; i <= kFrames; ++i) {
      Frame frame{"uav1", i, i * 40'000'000LL, cv::Mat(1080, 1920, CV_8UC1)};
      rng.fill(frame.image, cv::RNG::UNIFORM, 0, 256);
      sent.push_back(fnv1a64(frame.image.data, frame.image.total()));
      auto sample = to_msg(frame);
      ASSERT_TRUE(writer->write_reliably(sample, std::chrono::seconds(20)));
    }
    ASSERT_TRUE(writer->flush(std::chrono::seconds(20)));
  });
  std::vector<uint64_t> received;
  msg::Frame sample;
  while (static_cast<int>(received.size()) < kFrames && reader->wait_for_data(std::chrono::seconds(20))) {
    std::this_thread::sleep_for(std::chrono::milliseconds(30));  // a slow reader
    while (reader->take(sample)) {
      std::string why;
      auto frame = from_msg(sample, why);
      ASSERT_TRUE(frame) << why;
      EXPECT_EQ(frame->index, static_cast<int64_t>(received.size()) + 1);
      received.push_back(fnv1a64(frame->image.data, frame->image.total()));
    }
  }
  produce.join();
  EXPECT_EQ(received, sent);
  EXPECT_EQ(writer->samples_sent(), static_cast<uint64_t>(kFrames));
}

// A chain writer whose readers never all matched before its first sample ends its process (the
// launcher then respawns it with a new participant); once it has published, or without the opt-in
// (the downlink, whose ground reader may come late), the sample is given up as before.
TEST(Participant, AChainWriterWhoseReadersNeverMatchedThrowsOnItsFirstSampleOnly) {
  Participant writer_side(options("never-matched"));
  auto chain = writer_side.make_writer<msg::TrackListPubSubType>(kTracksTopic, TopicClass::Chain);
  chain->set_required_readers(1);
  chain->exit_if_readers_never_match();
  msg::TrackList sample;
  sample.stream_id("uav1");
  sample.frame_index(1);
  EXPECT_THROW(chain->write_reliably(sample, std::chrono::milliseconds(300)), ReadersNeverMatched);

  auto without_opt_in = writer_side.make_writer<msg::TrackListPubSubType>("uavmot/test/without-opt-in", TopicClass::Chain);
  without_opt_in->set_required_readers(1);
  EXPECT_FALSE(without_opt_in->write_reliably(sample, std::chrono::milliseconds(300)));

  {  // a reader matches, takes the first sample and leaves: the next sample's wait is no start-up fault
    Participant reader_side(options("leaves"));
    auto reader = reader_side.make_reader<msg::TrackListPubSubType>(kTracksTopic, TopicClass::Chain);
    ASSERT_TRUE(chain->wait_for_matched(1, std::chrono::seconds(10)));
    ASSERT_TRUE(chain->write_reliably(sample, std::chrono::seconds(10)));
    ASSERT_TRUE(chain->flush(std::chrono::seconds(10)));
  }
  ASSERT_TRUE(test_support::wait_until_unmatched(*chain));
  sample.frame_index(2);
  EXPECT_FALSE(chain->write_reliably(sample, std::chrono::milliseconds(300)));
}

// A tracker respawned with saved state reads the chain with ChainResume and gets what was published
// while it was down; every other reader (Chain) starts from the current sample.
TEST(Participant, AResumingReaderGetsTheChainHistoryAVolatileOneDoesNot) {
  Participant writer_side(options("writer"));
  Participant reader_side(options("readers"));
  auto writer = writer_side.make_writer<msg::TrackListPubSubType>(kTracksTopic, TopicClass::Chain);
  constexpr int kSamples = 5;
  for (int i = 1; i <= kSamples; ++i) {
    msg::TrackList sample;
    sample.stream_id("uav1");
    sample.frame_index(i);
    ASSERT_TRUE(writer->write(sample));
  }
  auto plain = reader_side.make_reader<msg::TrackListPubSubType>(kTracksTopic, TopicClass::Chain);
  auto resuming = reader_side.make_reader<msg::TrackListPubSubType>(kTracksTopic, TopicClass::ChainResume);
  ASSERT_TRUE(writer->wait_for_matched(2, std::chrono::seconds(10)));
  msg::TrackList sample;
  EXPECT_EQ(indices_taken(*resuming, sample, kSamples), (std::vector<int64_t>{1, 2, 3, 4, 5}));
  EXPECT_FALSE(plain->take(sample)) << "a volatile reader got history";
}

// A respawned segmentation (and motion with saved state) reads frames with FramesResume: it must get
// the writer's last 16 frames again, enough to hold the last frame its predecessor published (the
// shift check of the next frame needs it; bringup/qos/uavmot_qos.xml has the arithmetic).
TEST(Participant, AResumingFramesReaderGetsTheWritersLast16Frames) {
  Participant writer_side(options("frames-writer"));
  Participant reader_side(options("frames-readers"));
  auto writer = writer_side.make_writer<msg::FramePubSubType>(kFramesTopic, TopicClass::Frames);
  constexpr int kFrames = 20;
  for (int i = 1; i <= kFrames; ++i) {
    auto sample = to_msg(Frame{"uav1", i, i * 40'000'000LL, cv::Mat(48, 64, CV_8UC1, cv::Scalar(i))});
    ASSERT_TRUE(writer->write(sample));
  }
  auto plain = reader_side.make_reader<msg::FramePubSubType>(kFramesTopic, TopicClass::Frames);
  auto resuming = reader_side.make_reader<msg::FramePubSubType>(kFramesTopic, TopicClass::FramesResume);
  ASSERT_TRUE(writer->wait_for_matched(2, std::chrono::seconds(10)));
  msg::Frame sample;
  std::vector<int64_t> expected;
  for (int i = kFrames - 15; i <= kFrames; ++i) expected.push_back(i);
  EXPECT_EQ(indices_taken(*resuming, sample, expected.size()), expected);
  EXPECT_FALSE(plain->take(sample)) << "a volatile reader got history";
}

}  // namespace
}  // namespace uavmot::dds
