#include "uavmot/dds/health_reporter.hpp"

#include <thread>

#include <gtest/gtest.h>

#include "healthPubSubTypes.h"

namespace uavmot::dds {
namespace {

constexpr int kDomain = 100;  // of its own, so parallel test runs do not see each other

DdsOptions options(const std::string& name) {
  DdsOptions o;
  o.domain_id = kDomain;
  o.participant_name = name;
  return o;
}

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
      EXPECT_EQ(report.state(), msg::ComponentState::RUNNING);
      EXPECT_GE(report.frames_out(), last_frames_out);
      last_frames_out = report.frames_out();
      ++reports;
    }
  }
  EXPECT_GE(reports, 5) << "one report per 50 ms period was due during 20 s of frames";
  EXPECT_GT(last_frames_out, 0u);
}

}  // namespace
}  // namespace uavmot::dds
