#include "uavmot/downlink/downlink.hpp"

#include <cstdlib>
#include <memory>
#include <utility>
#include <vector>

#include <spdlog/spdlog.h>

#include "healthPubSubTypes.h"
#include "uavmot/core/app.hpp"
#include "uavmot/core/error.hpp"
#include "uavmot/core/shutdown.hpp"
#include "uavmot/dds/health_partitions.hpp"
#include "uavmot/dds/health_reporter.hpp"
#include "uavmot/dds/node_support.hpp"
#include "uavmot/dds/upstream_watch.hpp"
#include "uavmot/downlink/results_relay.hpp"

namespace uavmot::downlink {
namespace {

// The air side's participant: the link's options on the UAV's own domain and transport.
dds::DdsOptions air_options_of(const DownlinkOptions& o) {
  dds::DdsOptions air = o.link.dds;
  air.discovery_server.clear();
  air.domain_id = o.air_domain;
  air.participant_profile = o.air_transport;
  air.participant_name = "downlink-air";
  return air;
}

void log_summary(ResultsRelay& results, dds::TopicWriter<msg::ComponentHealthPubSubType>& link_health,
                 PreviewRelay* preview, const PreviewOptions& preview_options) {
  auto sent = [](const auto& w) { spdlog::info("{}: {} samples, {} bytes", w.topic(), w.samples_sent(), w.bytes_sent()); };
  sent(results.writer());
  sent(link_health);
  if (preview) {
    sent(preview->writer());
    spdlog::info("preview: {} of {} images due at {} Hz sent (the rest gave way to the {} kbit/s share)",
                 preview->writer().samples_sent(), preview->due(), preview_options.rate_hz, preview_options.kbps);
  }
  if (results.drops().tracks > 0) spdlog::warn("{} tracks had ids beyond 32 bits and were not sent", results.drops().tracks);
  if (results.drops().inexact_tracks > 0) {
    spdlog::warn("{} tracks were not float32 values and were sent rounded (not from uavmot's tracker?)",
                 results.drops().inexact_tracks);
  }
  if (results.drops().regions > 0) spdlog::warn("{} regions did not fit the compact fields and were not sent", results.drops().regions);
}

}  // namespace

int run_downlink(DownlinkOptions o) {
  auto& link_options = o.link.dds;
  if (o.air_domain == link_options.domain_id && o.air_transport == link_options.participant_profile) {
    throw InputError("--air-domain and --domain must differ when both sides use the same transport");
  }
  if (o.stream_id != "*" && o.streams != 1) throw InputError("--stream-id names one stream: --streams must be 1");
  // Only the link uses the discovery server: Fast DDS would turn every participant of this
  // process into a client of $ROS_DISCOVERY_SERVER, the shared-memory one too, which would then
  // never meet the UAV's processes.
  if (const char* env = std::getenv("ROS_DISCOVERY_SERVER")) {
    if (link_options.discovery_server.empty()) link_options.discovery_server = env;
    ::unsetenv("ROS_DISCOVERY_SERVER");
  }
  const dds::DdsOptions air_options = air_options_of(o);
  if (o.preview.rate_hz > 0 && o.preview.kbps > 0) {
    link_options.flow_limits.push_back({PreviewRelay::kFlow, static_cast<uint64_t>(o.preview.kbps * 1000.0)});
  }
  dds::Participant air(air_options);
  dds::Participant link(link_options);

  dds::HealthReporter health(link, "downlink", o.stream_id);
  // A named stream: the air readers take only its samples, so made-up ids on the UAV's domain can
  // neither fill their instance slots nor end the run with an end of stream of their own.
  const std::vector<std::string> own_streams = o.stream_id == "*" ? std::vector<std::string>{} : std::vector<std::string>{o.stream_id};
  ResultsRelay results(air, link, o.link.wait_subscribers, health, o.resume, own_streams);
  // One reader per air component's partition: only a component's own reports are passed on as its.
  std::vector<std::pair<std::string, std::unique_ptr<dds::TopicReader<msg::ComponentHealthPubSubType>>>> air_health;
  for (const char* component : {"source", "motion", "segmentation", "tracking"}) {
    air_health.emplace_back(dds::health_partition(component),
                            air.make_reader_in<msg::ComponentHealthPubSubType>(dds::health_partition(component), dds::kHealthTopic,
                                                                               dds::TopicClass::Health));
  }
  // The air's reports go on in the downlink's partition, the one its certificate may report in.
  auto link_health = link.make_writer_in<msg::ComponentHealthPubSubType>(dds::health_partition("downlink"), dds::kHealthTopic,
                                                                         dds::TopicClass::Health);
  for (const auto& [partition, reader] : air_health) health.watch(*reader);
  health.watch(*link_health);
  std::unique_ptr<PreviewRelay> preview;
  if (o.preview.rate_hz > 0) {
    preview = std::make_unique<PreviewRelay>(air, link, o.preview, own_streams);
    health.watch(preview->frames());
    health.watch(preview->writer());
    spdlog::info("preview: {} Hz, {} px wide, at most {} kbit/s", o.preview.rate_hz, o.preview.width, o.preview.kbps);
  }
  spdlog::info("domain {} ({}) -> domain {} ({}), {}, waiting for {} ground reader(s)", o.air_domain, o.air_transport,
               link_options.domain_id, link_options.participant_profile, o.link.mode, o.link.wait_subscribers);

  dds::UpstreamWatch upstream(o.upstream_timeout_s);
  while (!shutdown_requested() && results.streams_ended() < o.streams) {
    const bool any = results.pump();
    msg::ComponentHealth report;
    for (auto& [partition, reader] : air_health) {
      while (reader->take(report)) {
        if (!dds::health_report_trusted(partition, report.component_name().to_string())) continue;
        if (report.stream_id().to_string() == "*") report.stream_id(o.stream_id);
        link_health->write(report);
      }
    }
    if (preview) preview->pump(health);
    results.log_link_changes();
    health.set_bytes_out(results.writer().bytes_sent());
    health.tick();
    if (!any) {
      if (upstream.gone(results.writers_matched())) {
        return dds::give_up_on_upstream(upstream, health, "the air chain's results");
      }
      results.tracks().wait_for_data(std::chrono::milliseconds(50));
    }
  }
  // Every frame before the end of stream was acknowledged before the next was written
  // (lossless); only the end of stream itself may be unacknowledged when the ground's reader
  // exits right after reading it, which the writer learns only when that reader's participant
  // is gone. So: a short wait, and no failure.
  if (!results.writer().flush(std::chrono::seconds(5))) spdlog::warn("end of stream not acknowledged (the reader left?)");
  log_summary(results, *link_health, preview.get(), o.preview);
  health.report(msg::ComponentState::FINISHED);
  return results.streams_ended() >= o.streams ? kExitOk : kExitFailure;
}

}  // namespace uavmot::downlink
