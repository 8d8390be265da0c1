#include "uavmot/status/health_table.hpp"

#include <algorithm>

#include <fmt/format.h>

namespace uavmot::status {
namespace {

int chain_position(const std::string& component) {
  static const char* const kOrder[] = {"source", "motion", "segmentation", "tracking", "sink"};
  for (int i = 0; i < 5; ++i) {
    if (component == kOrder[i]) return i;
  }
  return 5;
}

std::string human_bytes_per_s(double b) {
  if (b >= 1e9) return fmt::format("{:.1f}G", b / 1e9);
  if (b >= 1e6) return fmt::format("{:.1f}M", b / 1e6);
  if (b >= 1e3) return fmt::format("{:.1f}k", b / 1e3);
  return fmt::format("{:.0f}", b);
}

// (now - before) / dt, or 0 when the counter went backwards (a respawned process counts from zero).
double rate(uint64_t now, uint64_t before, double dt) {
  return now >= before && dt > 0.0 ? static_cast<double>(now - before) / dt : 0.0;
}

}  // namespace

void HealthTable::update(const HealthReport& report) {
  auto [it, fresh] = entries_.try_emplace({report.stream_id, report.component});
  Entry& e = it->second;
  std::vector<TopicRate> topics;
  for (const auto& t : report.topics) topics.push_back({t.topic});
  if (!fresh) {
    const HealthReport& prev = e.report;
    if (report.stamp_ns < prev.stamp_ns) return;  // an older report delivered late
    const double dt = static_cast<double>(report.stamp_ns - prev.stamp_ns) / 1e9;
    // A respawned process starts counting from zero: no rate across the restart.
    const bool same_process = report.pid == prev.pid;
    e.bytes_per_s = same_process ? rate(report.bytes_out, prev.bytes_out, dt) : 0.0;
    for (size_t i = 0; i < report.topics.size() && same_process; ++i) {
      const TopicCounts& now = report.topics[i];
      for (const TopicCounts& before : prev.topics) {
        if (before.topic != now.topic) continue;
        topics[i] = {now.topic, rate(now.bytes_out, before.bytes_out, dt), rate(now.bytes_in, before.bytes_in, dt),
                     rate(now.samples_out, before.samples_out, dt), rate(now.samples_in, before.samples_in, dt)};
      }
    }
  }
  e.report = report;
  e.topics = std::move(topics);
}

std::vector<HealthRow> HealthTable::rows(int64_t now_ns) const {
  std::vector<HealthRow> out;
  for (const auto& [key, e] : entries_) {
    HealthRow row;
    row.report = e.report;
    row.bytes_per_s = e.bytes_per_s;
    row.topics = e.topics;
    row.age_s = std::max(0.0, static_cast<double>(now_ns - e.report.stamp_ns) / 1e9);
    row.stale = row.age_s > stale_after_s_;
    out.push_back(std::move(row));
  }
  std::stable_sort(out.begin(), out.end(), [](const HealthRow& a, const HealthRow& b) {
    // Chain order first: the source reports its stream id, the nodes serving every stream "*".
    const int pa = chain_position(a.report.component), pb = chain_position(b.report.component);
    if (pa != pb) return pa < pb;
    if (a.report.component != b.report.component) return a.report.component < b.report.component;
    return a.report.stream_id < b.report.stream_id;
  });
  return out;
}

std::string format_table(const std::vector<HealthRow>& rows) {
  std::string s = fmt::format("{:<10} {:<13} {:<12} {:>7} {:<16} {:>7} {:>7} {:>8} {:>9} {:>5} {:>15} {:>7} {:>7} {:>8}\n",
                              "STREAM", "COMPONENT", "HOST", "PID", "STATE", "FRAME", "RATE", "PROC ms", "LAT ms", "QUEUE",
                              "IN/OUT", "DROPPED", "INVALID", "OUT B/s");
  for (const HealthRow& row : rows) {
    const HealthReport& r = row.report;
    // Finished and failed components stop reporting on purpose: only a quiet live one is stale.
    const bool ended = r.state == "finished" || r.state == "failed";
    const std::string state = row.stale && !ended ? fmt::format("STALE {:.0f}s", row.age_s) : r.state;
    s += fmt::format("{:<10} {:<13} {:<12} {:>7} {:<16} {:>7} {:>7.1f} {:>8.1f} {:>9.1f} {:>5} {:>15} {:>7} {:>7} {:>8}\n",
                     r.stream_id.substr(0, 10), r.component.substr(0, 13), r.host.substr(0, 12), r.pid, state,
                     r.last_frame_index, r.rate_hz, r.processing_ms, r.latency_ms, r.queue_depth,
                     fmt::format("{}/{}", r.frames_in, r.frames_out), r.dropped, r.invalid_samples,
                     human_bytes_per_s(row.bytes_per_s));
    if (!r.message.empty()) s += fmt::format("{:<10} {:<13} {}\n", "", "", r.message);
    for (size_t i = 0; i < row.topics.size() && i < r.topics.size(); ++i) {
      const TopicRate& t = row.topics[i];
      const TopicCounts& c = r.topics[i];
      if (c.samples_out > 0) {
        s += fmt::format("{:<10} {:<13} {:<30} out {:>8}B/s {:>7.1f}/s\n", "", "", t.topic.substr(0, 30),
                         human_bytes_per_s(t.bytes_out_per_s), t.samples_out_per_s);
      }
      if (c.samples_in > 0) {
        s += fmt::format("{:<10} {:<13} {:<30} in  {:>8}B/s {:>7.1f}/s\n", "", "", t.topic.substr(0, 30),
                         human_bytes_per_s(t.bytes_in_per_s), t.samples_in_per_s);
      }
    }
  }
  if (rows.empty()) s += "(no component has reported on uavmot/health yet)\n";
  return s;
}

nlohmann::json to_json(const std::vector<HealthRow>& rows) {
  nlohmann::json out = nlohmann::json::array();
  for (const HealthRow& row : rows) {
    const HealthReport& r = row.report;
    nlohmann::json topics = nlohmann::json::array();
    for (size_t i = 0; i < r.topics.size(); ++i) {
      const TopicCounts& c = r.topics[i];
      const TopicRate rate = i < row.topics.size() ? row.topics[i] : TopicRate{c.topic};
      topics.push_back({{"topic", c.topic}, {"samples_out", c.samples_out}, {"bytes_out", c.bytes_out},
                        {"samples_in", c.samples_in}, {"bytes_in", c.bytes_in}, {"bytes_out_per_s", rate.bytes_out_per_s},
                        {"bytes_in_per_s", rate.bytes_in_per_s}, {"samples_out_per_s", rate.samples_out_per_s},
                        {"samples_in_per_s", rate.samples_in_per_s}});
    }
    out.push_back({{"stream_id", r.stream_id}, {"component", r.component}, {"host", r.host}, {"pid", r.pid},
                   {"state", r.state}, {"stamp_ns", r.stamp_ns}, {"last_frame_index", r.last_frame_index},
                   {"rate_hz", r.rate_hz}, {"processing_ms", r.processing_ms}, {"latency_ms", r.latency_ms},
                   {"queue_depth", r.queue_depth}, {"frames_in", r.frames_in}, {"frames_out", r.frames_out},
                   {"dropped", r.dropped}, {"invalid_samples", r.invalid_samples}, {"bytes_out", r.bytes_out},
                   {"bytes_per_s", row.bytes_per_s}, {"age_s", row.age_s}, {"stale", row.stale},
                   {"message", r.message}, {"topics", topics}});
  }
  return out;
}

}  // namespace uavmot::status
