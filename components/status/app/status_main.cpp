// uavmot-status: the live table of every component's health, from uavmot/health.
//
//   uavmot status                 redraws in place every second on a terminal, else prints a table per --interval
//   uavmot status --once [--json] one table (or JSON array) after a short discovery wait, for scripts
//
// The health topic is transient-local, so the last report of components already running (or
// already finished) arrives as soon as this process has discovered them.

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <iostream>
#include <thread>
#include <utility>
#include <vector>

#include "healthPubSubTypes.h"
#include "uavmot/core/app.hpp"
#include "uavmot/core/shutdown.hpp"
#include "uavmot/dds/health_partitions.hpp"
#include "uavmot/dds/node_options.hpp"
#include "uavmot/dds/node_support.hpp"
#include "uavmot/status/health_table.hpp"

namespace uavmot {
namespace {

std::string state_name(msg::ComponentState state) {
  switch (state) {
    case msg::ComponentState::STARTING: return "starting";
    case msg::ComponentState::RUNNING: return "running";
    case msg::ComponentState::FINISHED: return "finished";
    case msg::ComponentState::FAILED: return "failed";
  }
  return "unknown";
}

status::HealthReport from_msg(const msg::ComponentHealth& h) {
  status::HealthReport r;
  r.stream_id = h.stream_id().to_string();
  r.component = h.component_name().to_string();
  r.host = h.host().to_string();
  r.pid = h.pid();
  r.state = state_name(h.state());
  r.stamp_ns = h.stamp_ns();
  r.last_frame_index = h.last_frame_index();
  r.rate_hz = h.rate_hz();
  r.processing_ms = h.processing_ms();
  r.latency_ms = h.latency_ms();
  r.queue_depth = h.queue_depth();
  r.frames_in = h.frames_in();
  r.frames_out = h.frames_out();
  r.dropped = h.dropped();
  r.invalid_samples = h.invalid_samples();
  r.bytes_out = h.bytes_out();
  r.message = h.message().to_string();
  for (const auto& t : h.topics()) {
    r.topics.push_back({t.topic().to_string(), t.samples_out(), t.bytes_out(), t.samples_in(), t.bytes_in()});
  }
  return r;
}

int status_main(int argc, char** argv) {
  dds::NodeOptions node;
  node.heap_reserve_mb = 0;  // handles no frames
  node.log_level = "warn";
  bool once = false, json = false;
  double interval_s = 1.0, wait_s = 2.0, stale_s = 3.0;
  return run_app(argc, argv, "status", "live table of every component's rate, latency, queue and drops (uavmot/health)",
                 [&](CLI::App& app) {
    app.add_flag("--once", once, "print one table after --wait seconds of discovery and exit (1 if nothing reported)");
    app.add_flag("--json", json, "JSON instead of text: one array per table (JSON Lines when repeating)");
    app.add_option("--interval", interval_s, "seconds between tables")->check(uavmot::positive_finite())->capture_default_str();
    app.add_option("--wait", wait_s, "--once: seconds to discover components and collect reports")
        ->check(uavmot::non_negative_finite())->capture_default_str();
    app.add_option("--stale", stale_s, "a component with no report for this long is marked stale (s)")
        ->check(uavmot::positive_finite())->capture_default_str();
    dds::add_node_options(app, node);
    return [&]() -> int {
      dds::finalize(node, "status");
      install_shutdown_handler();
      dds::Participant participant(node.dds);
      // One reader per component's partition: a report counts only as its partition's component's
      // (with security on, a node may report in its own partition only; health_partitions.hpp).
      std::vector<std::pair<std::string, std::unique_ptr<dds::TopicReader<msg::ComponentHealthPubSubType>>>> readers;
      for (const auto& component : dds::health_components()) {
        const std::string partition = dds::health_partition(component);
        readers.emplace_back(partition, participant.make_reader_in<msg::ComponentHealthPubSubType>(partition, dds::kHealthTopic,
                                                                                                   dds::TopicClass::Health));
      }
      status::HealthTable table(stale_s);
      const bool redraw = !json && !once && ::isatty(STDOUT_FILENO);

      auto collect = [&](std::chrono::steady_clock::time_point until) {
        msg::ComponentHealth sample;
        while (!shutdown_requested()) {
          for (auto& [partition, reader] : readers) {
            while (reader->take(sample)) {
              if (dds::health_report_trusted(partition, sample.component_name().to_string())) table.update(from_msg(sample));
            }
          }
          const auto left = until - std::chrono::steady_clock::now();
          if (left <= std::chrono::milliseconds(0)) break;
          std::this_thread::sleep_for(std::min(std::chrono::duration_cast<std::chrono::milliseconds>(left) + std::chrono::milliseconds(1),
                                               std::chrono::milliseconds(50)));
        }
      };
      auto print = [&]() {
        const auto rows = table.rows(dds::wall_clock_ns());
        if (json) {
          std::cout << status::to_json(rows).dump() << '\n';
        } else {
          if (redraw) std::cout << "\033[H\033[2J";  // home + clear: redraw in place
          std::cout << status::format_table(rows);
          if (!redraw) std::cout << '\n';
        }
        std::cout.flush();
      };

      auto next = std::chrono::steady_clock::now() + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                                         std::chrono::duration<double>(once ? wait_s : 0.3));
      collect(next);
      print();
      if (once) return table.empty() ? kExitFailure : kExitOk;
      const auto period = std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(interval_s));
      while (!shutdown_requested()) {
        next += period;
        collect(next);
        if (!shutdown_requested()) print();
      }
      return kExitOk;
    };
  });
}

}  // namespace
}  // namespace uavmot

int main(int argc, char** argv) { return uavmot::status_main(argc, argv); }
