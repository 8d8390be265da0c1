#pragma once
// The last health report of every (stream, component), with what a single report cannot say:
// the output rate in bytes/s (from successive bytes_out) and whether the component went quiet.
// Plain data in, text or JSON out: no DDS here, so it is testable on its own.

#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace uavmot::status {

// What a component wrote to / read from one topic since it started (TopicTraffic in idl/health.idl).
struct TopicCounts {
  std::string topic;
  uint64_t samples_out = 0, bytes_out = 0, samples_in = 0, bytes_in = 0;
};

// Per-topic rates between two reports of the same process.
struct TopicRate {
  std::string topic;
  double bytes_out_per_s = 0.0, bytes_in_per_s = 0.0, samples_out_per_s = 0.0, samples_in_per_s = 0.0;
};

// One ComponentHealth sample (idl/health.idl) as plain fields.
struct HealthReport {
  std::string stream_id;
  std::string component;
  std::string host;
  uint32_t pid = 0;
  std::string state;  // starting | running | finished | failed
  int64_t stamp_ns = 0;  // sender's wall clock
  int64_t last_frame_index = 0;
  double rate_hz = 0.0;
  double processing_ms = 0.0;
  double latency_ms = 0.0;
  uint32_t queue_depth = 0;
  uint64_t frames_in = 0;
  uint64_t frames_out = 0;
  uint64_t dropped = 0;
  uint64_t invalid_samples = 0;
  uint64_t bytes_out = 0;
  std::string message;
  std::vector<TopicCounts> topics;
};

struct HealthRow {
  HealthReport report;
  double bytes_per_s = 0.0;  // between the last two reports of the same process
  std::vector<TopicRate> topics;  // likewise, per topic (one entry per topic in the report)
  double age_s = 0.0;        // since the last report was stamped
  bool stale = false;        // no report for longer than the stale limit
};

class HealthTable {
 public:
  explicit HealthTable(double stale_after_s = 3.0) : stale_after_s_(stale_after_s) {}

  void update(const HealthReport& report);
  // Rows in chain order (source, motion, segmentation, tracking, sink, others by name), then by stream.
  // `now_ns` is the wall clock: stamps are wall-clock too, so a report that a late subscriber
  // receives long after it was sent (transient-local history) is already stale.
  std::vector<HealthRow> rows(int64_t now_ns) const;
  bool empty() const { return entries_.empty(); }

 private:
  struct Entry {
    HealthReport report;
    double bytes_per_s = 0.0;
    std::vector<TopicRate> topics;
  };
  double stale_after_s_;
  std::map<std::pair<std::string, std::string>, Entry> entries_;
};

// A fixed-width text table with a header line; under each row, one line per topic it wrote or
// read with bytes/s and samples/s in and out.
std::string format_table(const std::vector<HealthRow>& rows);
// An array of objects, one per row, with the report's fields plus bytes_per_s, age_s and stale;
// `topics` holds the per-topic counts with their rates (bytes_out_per_s, ...).
nlohmann::json to_json(const std::vector<HealthRow>& rows);

}  // namespace uavmot::status
