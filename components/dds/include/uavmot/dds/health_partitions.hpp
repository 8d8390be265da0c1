#pragma once
// Who may report as whom on uavmot/health. Every component publishes its reports in a DDS
// partition named after itself; tools/make_security.sh lets each node's certificate publish
// health in its own partition only. A reader that acts on a report (the launcher's watchdog,
// `uavmot status`) reads each partition with a reader of its own and trusts a report only when
// its partition may carry that component's reports, so a node cannot pass itself off as another.

#include <string>
#include <vector>

namespace uavmot::dds {

// Every component that reports health (the partitions a reader of all reports reads).
const std::vector<std::string>& health_components();

// The partition `component` publishes its reports in.
inline std::string health_partition(const std::string& component) { return component; }

// Whether a report naming `component` that arrived in `partition` may be taken as that
// component's: its own partition, or the downlink's for the air components it forwards.
bool health_report_trusted(const std::string& partition, const std::string& component);

}  // namespace uavmot::dds
