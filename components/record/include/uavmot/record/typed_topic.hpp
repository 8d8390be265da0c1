#pragma once
// Calls `fn.template operator()<PubSubType>()` with the generated Fast DDS type of a uavmot topic,
// so the recorder and replayer create typed endpoints from a topic name.

#include <string>

#include "framePubSubTypes.h"
#include "healthPubSubTypes.h"
#include "motionPubSubTypes.h"
#include "segmentationPubSubTypes.h"
#include "tracksPubSubTypes.h"
#include "uavmot/core/error.hpp"
#include "uavmot/dds/topics.hpp"

namespace uavmot::record {

template <class Fn>
decltype(auto) with_topic_type(const std::string& topic, Fn&& fn) {
  if (topic == dds::kFramesTopic) return fn.template operator()<msg::FramePubSubType>();
  if (topic == dds::kMotionTopic) return fn.template operator()<msg::MotionEstimatePubSubType>();
  if (topic == dds::kSegmentationTopic) return fn.template operator()<msg::SegmentationPubSubType>();
  if (topic == dds::kTracksTopic) return fn.template operator()<msg::TrackListPubSubType>();
  if (topic == dds::kHealthTopic) return fn.template operator()<msg::ComponentHealthPubSubType>();
  throw InputError("'" + topic + "' is not a uavmot topic");
}

}  // namespace uavmot::record
