// uavmot-test-forge-health: a participant that reports on uavmot/health in the name of
// --component from partition --partition (default: the component's own), for --seconds: a
// forged report, when its certificate is another node's. Exit 0 after writing, 3 when the writer
// could not even be created (refused by access control).

#include <unistd.h>

#include <memory>
#include <thread>

#include <spdlog/spdlog.h>

#include "healthPubSubTypes.h"
#include "uavmot/core/app.hpp"
#include "uavmot/core/error.hpp"
#include "uavmot/core/shutdown.hpp"
#include "uavmot/dds/health_partitions.hpp"
#include "uavmot/dds/node_options.hpp"

namespace uavmot {
namespace {

int forge_main(int argc, char** argv) {
  dds::NodeOptions node;
  std::string component, partition, stream = "forged";
  double seconds = 10.0;
  return run_app(argc, argv, "test-forge-health", "report on uavmot/health in another component's name (tests)",
                 [&](CLI::App& app) {
    app.add_option("--component", component, "component name the reports claim")->required();
    app.add_option("--partition", partition, "partition to publish in (default: the component's own)");
    app.add_option("--stream", stream, "stream id of the reports")->capture_default_str();
    app.add_option("--seconds", seconds, "how long to keep reporting")->capture_default_str();
    node.heap_reserve_mb = 0;
    dds::add_node_options(app, node);
    return [&]() -> int {
      dds::finalize(node, "forge-health");
      install_shutdown_handler();
      if (partition.empty()) partition = dds::health_partition(component);
      dds::Participant participant(node.dds);
      std::unique_ptr<dds::TopicWriter<msg::ComponentHealthPubSubType>> writer;
      try {
        writer = participant.make_writer_in<msg::ComponentHealthPubSubType>(partition, dds::kHealthTopic, dds::TopicClass::Health);
      } catch (const InputError& e) {
        spdlog::info("writer refused: {}", e.what());
        return 3;
      }
      char host[64] = {};
      ::gethostname(host, sizeof(host) - 1);
      const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
      uint64_t written = 0;
      for (int64_t k = 1; std::chrono::steady_clock::now() < end && !shutdown_requested(); ++k) {
        msg::ComponentHealth sample;
        sample.stream_id(stream);
        sample.component_name(component);
        sample.host(host);
        sample.pid(static_cast<uint32_t>(::getpid()));
        sample.state(msg::ComponentState::RUNNING);
        sample.stamp_ns(std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::system_clock::now().time_since_epoch()).count());
        sample.last_frame_index(k);
        if (writer->write(sample)) ++written;
        std::this_thread::sleep_for(std::chrono::milliseconds(200));
      }
      spdlog::info("wrote {} reports as {} in partition {}; matched {} reader(s)", written, component, partition, writer->matched());
      return 0;
    };
  });
}

}  // namespace
}  // namespace uavmot

int main(int argc, char** argv) { return uavmot::forge_main(argc, argv); }
