#include "uavmot/record/qos_description.hpp"

namespace uavmot::record {
namespace fdds = eprosima::fastdds::dds;

QosDescription describe_qos(const fdds::DataReaderQos& qos) {
  QosDescription d;
  d.reliability = qos.reliability().kind == fdds::RELIABLE_RELIABILITY_QOS ? "RELIABLE" : "BEST_EFFORT";
  switch (qos.durability().kind) {
    case fdds::VOLATILE_DURABILITY_QOS: d.durability = "VOLATILE"; break;
    case fdds::TRANSIENT_LOCAL_DURABILITY_QOS: d.durability = "TRANSIENT_LOCAL"; break;
    case fdds::TRANSIENT_DURABILITY_QOS: d.durability = "TRANSIENT"; break;
    case fdds::PERSISTENT_DURABILITY_QOS: d.durability = "PERSISTENT"; break;
  }
  d.history = qos.history().kind == fdds::KEEP_ALL_HISTORY_QOS ? "KEEP_ALL" : "KEEP_LAST";
  d.depth = qos.history().kind == fdds::KEEP_ALL_HISTORY_QOS ? 0 : qos.history().depth;
  return d;
}

}  // namespace uavmot::record
