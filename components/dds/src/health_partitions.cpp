#include "uavmot/dds/health_partitions.hpp"

#include <algorithm>

namespace uavmot::dds {

const std::vector<std::string>& health_components() {
  static const std::vector<std::string> all = {"source", "motion", "segmentation", "tracking", "downlink",
                                               "sink",   "framesink", "view"};
  return all;
}

bool health_report_trusted(const std::string& partition, const std::string& component) {
  if (partition == health_partition(component)) return true;
  // uavmot-downlink passes the UAV's own components' reports on to the link in its partition.
  static const std::vector<std::string> forwarded = {"source", "motion", "segmentation", "tracking"};
  return partition == health_partition("downlink") &&
         std::find(forwarded.begin(), forwarded.end(), component) != forwarded.end();
}

}  // namespace uavmot::dds
