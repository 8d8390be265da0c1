// The status table: latest report per (stream, component), bytes/s from successive reports,
// staleness from the report stamps, chain ordering, text and JSON output.

#include <gtest/gtest.h>

#include "uavmot/status/health_table.hpp"

namespace uavmot::status {
namespace {

constexpr int64_t kSecond = 1'000'000'000;

HealthReport report(const std::string& component, int64_t stamp_s, uint64_t bytes_out, uint32_t pid = 100) {
  HealthReport r;
  r.stream_id = "*";
  r.component = component;
  r.host = "air1";
  r.pid = pid;
  r.state = "running";
  r.stamp_ns = stamp_s * kSecond;
  r.rate_hz = 25.0;
  r.frames_in = 10;
  r.frames_out = 9;
  r.bytes_out = bytes_out;
  return r;
}

TEST(HealthTable, KeepsTheLatestReportPerStreamAndComponent) {
  HealthTable table;
  table.update(report("motion", 10, 0));
  auto second = report("motion", 11, 0);
  second.last_frame_index = 42;
  table.update(second);
  auto other_stream = report("motion", 11, 0);
  other_stream.stream_id = "uav2";
  table.update(other_stream);
  auto source = report("source", 11, 0);
  source.stream_id = "uav1";
  table.update(source);
  const auto rows = table.rows(11 * kSecond);
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[0].report.component, "source");  // the chain's head first, whatever its stream
  EXPECT_EQ(rows[1].report.stream_id, "*");
  EXPECT_EQ(rows[1].report.last_frame_index, 42);
  EXPECT_EQ(rows[2].report.stream_id, "uav2");
}

TEST(HealthTable, BytesPerSecondComesFromSuccessiveReports) {
  HealthTable table;
  table.update(report("source", 10, 1'000'000));
  EXPECT_EQ(table.rows(10 * kSecond)[0].bytes_per_s, 0.0);  // one report: no rate yet
  table.update(report("source", 12, 51'000'000));
  EXPECT_DOUBLE_EQ(table.rows(12 * kSecond)[0].bytes_per_s, 25'000'000.0);
}

TEST(HealthTable, RespawnedProcessDoesNotGiveANegativeOrHugeRate) {
  HealthTable table;
  table.update(report("tracking", 10, 5'000'000, 100));
  table.update(report("tracking", 11, 1'000, 200));  // new pid, counters from zero
  EXPECT_EQ(table.rows(11 * kSecond)[0].bytes_per_s, 0.0);
  table.update(report("tracking", 12, 3'000, 200));
  EXPECT_DOUBLE_EQ(table.rows(12 * kSecond)[0].bytes_per_s, 2'000.0);
}

TEST(HealthTable, PerTopicRatesInAndOutComeFromSuccessiveReports) {
  HealthTable table;
  auto first = report("downlink", 10, 0);
  first.topics = {{"uavmot/downlink/results", 100, 150'000, 0, 0}, {"uavmot/tracks", 0, 0, 100, 600'000}};
  table.update(first);
  auto second = report("downlink", 12, 0);
  second.topics = {{"uavmot/downlink/results", 150, 250'000, 0, 0}, {"uavmot/tracks", 0, 0, 150, 900'000},
                   {"uavmot/health", 2, 500, 0, 0}};  // a topic new in this report: no rate yet
  table.update(second);
  const auto rows = table.rows(12 * kSecond);
  ASSERT_EQ(rows[0].topics.size(), 3u);
  EXPECT_EQ(rows[0].topics[0].topic, "uavmot/downlink/results");
  EXPECT_DOUBLE_EQ(rows[0].topics[0].bytes_out_per_s, 50'000.0);
  EXPECT_DOUBLE_EQ(rows[0].topics[0].samples_out_per_s, 25.0);
  EXPECT_DOUBLE_EQ(rows[0].topics[1].bytes_in_per_s, 150'000.0);
  EXPECT_EQ(rows[0].topics[1].bytes_out_per_s, 0.0);
  EXPECT_EQ(rows[0].topics[2].bytes_out_per_s, 0.0);

  const std::string text = format_table(rows);
  EXPECT_NE(text.find("uavmot/downlink/results        out    50.0kB/s    25.0/s"), std::string::npos) << text;
  EXPECT_NE(text.find("uavmot/tracks                  in    150.0kB/s    25.0/s"), std::string::npos) << text;
  const auto j = to_json(rows);
  EXPECT_EQ(j[0]["topics"][0]["bytes_out"], 250'000);
  EXPECT_EQ(j[0]["topics"][1]["bytes_in_per_s"], 150'000.0);

  auto respawned = report("downlink", 13, 0, 200);  // counters from zero in a new process
  respawned.topics = {{"uavmot/downlink/results", 1, 100, 0, 0}};
  table.update(respawned);
  EXPECT_EQ(table.rows(13 * kSecond)[0].topics[0].bytes_out_per_s, 0.0);
}

TEST(HealthTable, OlderReportDeliveredLateIsIgnored) {
  HealthTable table;
  table.update(report("sink", 12, 2'000));
  table.update(report("sink", 11, 1'000));
  const auto rows = table.rows(12 * kSecond);
  EXPECT_EQ(rows[0].report.bytes_out, 2'000u);
  EXPECT_EQ(rows[0].bytes_per_s, 0.0);
}

TEST(HealthTable, ComponentIsStaleAfterThreeSecondsWithoutAReport) {
  HealthTable table;
  table.update(report("motion", 10, 0));
  EXPECT_FALSE(table.rows(12 * kSecond)[0].stale);
  EXPECT_FALSE(table.rows(13 * kSecond)[0].stale);
  const auto late = table.rows(13 * kSecond + 1);
  EXPECT_TRUE(late[0].stale);
  EXPECT_NEAR(late[0].age_s, 3.0, 1e-6);
  table.update(report("motion", 14, 0));  // it speaks again
  EXPECT_FALSE(table.rows(14 * kSecond)[0].stale);
}

TEST(HealthTable, RowsFollowTheChainOrder) {
  HealthTable table;
  for (const char* c : {"sink", "view", "tracking", "source", "segmentation", "motion"}) table.update(report(c, 10, 0));
  std::vector<std::string> order;
  for (const auto& row : table.rows(10 * kSecond)) order.push_back(row.report.component);
  EXPECT_EQ(order, (std::vector<std::string>{"source", "motion", "segmentation", "tracking", "sink", "view"}));
}

TEST(FormatTable, ShowsEveryColumnAndMarksOnlyQuietLiveComponentsStale) {
  HealthTable table;
  auto motion = report("motion", 10, 0);
  motion.processing_ms = 12.34;
  motion.latency_ms = 56.78;
  motion.queue_depth = 3;
  motion.dropped = 7;
  motion.invalid_samples = 2;
  motion.last_frame_index = 123;
  table.update(motion);
  motion.stamp_ns = 11 * kSecond;
  motion.bytes_out = 2'500'000;
  table.update(motion);
  auto sink = report("sink", 10, 0);
  sink.state = "finished";
  sink.message = "all streams ended";
  table.update(sink);

  const std::string fresh = format_table(table.rows(11 * kSecond));
  EXPECT_NE(fresh.find("STREAM"), std::string::npos);
  EXPECT_NE(fresh.find("OUT B/s"), std::string::npos);
  for (const char* expected : {"motion", "air1", "running", "123", "25.0", "12.3", "56.8", "10/9", "2.5M", "finished",
                               "all streams ended"}) {
    EXPECT_NE(fresh.find(expected), std::string::npos) << expected << "\n" << fresh;
  }
  EXPECT_EQ(fresh.find("STALE"), std::string::npos) << fresh;

  const std::string quiet = format_table(table.rows(20 * kSecond));
  EXPECT_NE(quiet.find("STALE 9s"), std::string::npos) << quiet;  // motion, 9 s after its last report
  EXPECT_EQ(quiet.find("STALE 10s"), std::string::npos) << quiet;  // the finished sink stays "finished"
  EXPECT_NE(quiet.find("finished"), std::string::npos) << quiet;
}

TEST(FormatTable, SaysSoWhenNothingReported) {
  EXPECT_NE(format_table({}).find("no component has reported"), std::string::npos);
}

TEST(ToJson, CarriesTheReportAndTheDerivedFields) {
  HealthTable table;
  table.update(report("source", 10, 0));
  table.update(report("source", 11, 4'000));
  const auto j = to_json(table.rows(15 * kSecond));
  ASSERT_EQ(j.size(), 1u);
  EXPECT_EQ(j[0]["component"], "source");
  EXPECT_EQ(j[0]["frames_out"], 9);
  EXPECT_EQ(j[0]["rate_hz"], 25.0);
  EXPECT_EQ(j[0]["bytes_per_s"], 4000.0);
  EXPECT_EQ(j[0]["stale"], true);
  EXPECT_DOUBLE_EQ(j[0]["age_s"].get<double>(), 4.0);
}

}  // namespace
}  // namespace uavmot::status
