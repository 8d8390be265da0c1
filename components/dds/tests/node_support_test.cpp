#include "uavmot/dds/node_support.hpp"

#include <cstdio>
#include <cstdlib>

#include <gtest/gtest.h>

#include "test_participants.hpp"
#include "tracksPubSubTypes.h"

namespace uavmot::dds {
namespace {

constexpr int kDomain = 101;  // of its own, so parallel test runs do not see each other

DdsOptions options(const std::string& name) { return test_support::options_on(kDomain, name); }

msg::TrackList frame_output(int64_t index) {
  msg::TrackList sample;
  sample.stream_id("uav1");
  sample.frame_index(index);
  return sample;
}

// Lossless: a frame output that its reader does not take (here: the reader left and no new one
// came) ends the process instead of being given up, which would lose the frame for good; the
// launcher's respawn redoes it.
TEST(NodeSupport, ALosslessFrameOutputItsReadersDidNotTakeEndsTheProcess) {
  Participant node_side(options("node"));
  HealthReporter health(node_side, "tracking", "*", std::chrono::hours(1));
  auto writer = node_side.make_writer<msg::TrackListPubSubType>(kTracksTopic, TopicClass::Chain);
  writer->set_required_readers(1);
  int published_hook_calls = 0;
  const PublishedHook published = [&](const std::string&, int64_t) { ++published_hook_calls; };
  {
    Participant reader_side(options("reader"));
    auto reader = reader_side.make_reader<msg::TrackListPubSubType>(kTracksTopic, TopicClass::Chain);
    ASSERT_TRUE(writer->wait_for_matched(1, std::chrono::seconds(10)));
    auto first = frame_output(1);
    publish_frame_output(*writer, first, DeliveryMode::Lossless, health, published, "uav1", 1, 1.0, 0);
    ASSERT_TRUE(writer->flush(std::chrono::seconds(10)));
  }
  EXPECT_EQ(published_hook_calls, 1);
  ASSERT_TRUE(test_support::wait_until_unmatched(*writer));

  auto second = frame_output(2);
  EXPECT_THROW(publish_frame_output(*writer, second, DeliveryMode::Lossless, health, published, "uav1", 2, 1.0, 0,
                                    std::chrono::milliseconds(300)),
               OutputNotDelivered);
  EXPECT_EQ(published_hook_calls, 1) << "an undelivered frame counted as published (its state would be saved)";
  EXPECT_EQ(health.dropped_count(), 0u);
}

// A stop (SIGTERM) that ends a lossless frame output's wait for its readers: the frame was not sent,
// so it must not count as published (its state would be saved and a resumed run would skip it).
// The stop flag is process-wide, so the case runs in a child process of its own (a death test that
// re-runs this binary) and reports by its exit code.
TEST(NodeSupport, AStopDuringALosslessWaitDoesNotCountTheFrameAsPublished) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  auto stop_while_waiting = [] {
    Participant node_side(options("stopping-node"));
    HealthReporter health(node_side, "tracking", "*", std::chrono::hours(1));
    auto writer = node_side.make_writer<msg::TrackListPubSubType>(kTracksTopic, TopicClass::Chain);
    writer->set_required_readers(1);  // and no reader comes
    int published_hook_calls = 0;
    const PublishedHook published = [&](const std::string&, int64_t) { ++published_hook_calls; };
    request_shutdown();
    auto output = frame_output(1);
    try {
      publish_frame_output(*writer, output, DeliveryMode::Lossless, health, published, "uav1", 1, 1.0, 0,
                           std::chrono::seconds(30));
    } catch (const std::exception& e) {
      std::fprintf(stderr, "threw: %s\n", e.what());
      std::_Exit(3);
    }
    std::fprintf(stderr, "published hook calls: %d, dropped: %llu\n", published_hook_calls,
                 static_cast<unsigned long long>(health.dropped_count()));
    std::_Exit(published_hook_calls == 0 && health.dropped_count() == 0 ? 0 : 4);
  };
  EXPECT_EXIT(stop_while_waiting(), ::testing::ExitedWithCode(0), "published hook calls: 0, dropped: 0");
}

}  // namespace
}  // namespace uavmot::dds
