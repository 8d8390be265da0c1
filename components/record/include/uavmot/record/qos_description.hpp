#pragma once
// The QoS of a Fast DDS endpoint as the strings a recording's channel metadata stores.

#include <fastdds/dds/subscriber/qos/DataReaderQos.hpp>

#include "uavmot/record/topic_catalog.hpp"

namespace uavmot::record {

QosDescription describe_qos(const eprosima::fastdds::dds::DataReaderQos& qos);

}  // namespace uavmot::record
