#include "uavmot/dds/health_reporter.hpp"

#include <thread>

#include <gtest/gtest.h>

#include "healthPubSubTypes.h"
#include "test_participants.hpp"

namespace uavmot::dds {
namespace {

constexpr int kDomain = 100;  // of its own, so parallel test runs do not see each other

DdsOptions options(const std::string& name) { return test_support::options_on(kDomain, name); }

// A node busy with a backlog never returns to the loop where it calls tick(): frame_out() alone
// must keep the reports coming (seen: motion under ASan, and tracking on a loaded host, showed no
// report for seconds while they were the bottleneck of the chain).
TEST(HealthReporter, ReportsWhileBusyWithoutTick) {
  Participant node_side(options("node"));
  Participant observer_side(options("observer"));
  HealthReporter health(node_side, "motion", "*", std::chrono::milliseconds(50));
  auto reader = observer_side.make_reader<msg::ComponentHealthPubSubType>(kHealthTopic, TopicClass::Health);

  // Frames until five reports arrived: one is due every 50 ms, so that takes ~0.3 s once the
  // reader matched; the deadline only bounds discovery on a loaded host or under TSan.
  uint64_t last_frames_out = 0;
  int reports = 0;
  msg::ComponentHealth report;
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  for (int64_t frame = 1; reports < 5 && std::chrono::steady_clock::now() < end; ++frame) {
    health.frame_in();
    std::this_thread::sleep_for(std::chrono::milliseconds(5));  // "processing"
    health.frame_out(frame, 5.0);
    while (reader->take(report)) {
      if (report.state() == msg::ComponentState::STARTING && reports == 0) continue;  // the one made at once
      EXPECT_EQ(report.state(), msg::ComponentState::RUNNING);
      EXPECT_GE(report.frames_out(), last_frames_out);
      last_frames_out = report.frames_out();
      ++reports;
    }
  }
  EXPECT_GE(reports, 5) << "one report per 50 ms period was due during 20 s of frames";
  EXPECT_GT(last_frames_out, 0u);
}

// The first report goes out when the reporter is made, before any tick or frame: the launcher's
// watchdog only watches a process that has reported, so one stopped in its first second must
// already have been seen (fault injection stopped the source before its first periodic report).
TEST(HealthReporter, ReportsStartingAsSoonAsItIsMade) {
  Participant node_side(options("node"));
  Participant observer_side(options("observer"));
  HealthReporter health(node_side, "source", "*", std::chrono::hours(1));  // no periodic report due
  auto reader = observer_side.make_reader<msg::ComponentHealthPubSubType>(kHealthTopic, TopicClass::Health);
  msg::ComponentHealth report;
  bool got = false;
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(20);  // discovery only
  while (!got && std::chrono::steady_clock::now() < end) {
    got = reader->take(report);
    if (!got) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ASSERT_TRUE(got) << "no report from a reporter made 20 s ago whose period is an hour";
  EXPECT_EQ(report.state(), msg::ComponentState::STARTING);
  EXPECT_EQ(report.component_name().to_string(), "source");
  EXPECT_EQ(report.frames_out(), 0u);
}

}  // namespace
}  // namespace uavmot::dds
