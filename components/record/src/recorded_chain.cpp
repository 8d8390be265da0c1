#include "uavmot/record/recorded_chain.hpp"

#include <map>

#include <spdlog/spdlog.h>

#include "motionPubSubTypes.h"
#include "segmentationPubSubTypes.h"
#include "uavmot/core/error.hpp"
#include "uavmot/core/frame_pairing.hpp"
#include "uavmot/dds/chain_convert.hpp"
#include "uavmot/dds/topics.hpp"
#include "uavmot/mcap/reader.hpp"
#include "uavmot/record/cdr_payload.hpp"

namespace uavmot::record {

RecordedChainCounts read_recorded_chain(const std::string& path, const RecordedPairHandler& handle) {
  mcap::Reader reader;
  reader.open(path);
  bool has_motion = false, has_segmentation = false;
  for (const auto& [id, channel] : reader.channels()) {
    has_motion = has_motion || channel.topic == dds::kMotionTopic;
    has_segmentation = has_segmentation || channel.topic == dds::kSegmentationTopic;
  }
  if (!has_motion || !has_segmentation) {
    throw InputError(path + ": the recording has no " + (has_motion ? dds::kSegmentationTopic : dds::kMotionTopic) +
                     " topic; re-running tracking needs both uavmot/motion and uavmot/segmentation");
  }

  struct Stream {
    FramePairing<MotionEstimate, SegmentationResult> pairing;
  };
  std::map<std::string, Stream> streams;
  RecordedChainCounts counts;
  auto drain = [&](const std::string& id, Stream& s) {
    while (auto pair = s.pairing.pop()) {
      handle(id, pair->first, pair->second);
      ++counts.pairs;
    }
  };

  msg::MotionEstimatePubSubType motion_type;
  msg::SegmentationPubSubType segmentation_type;
  msg::MotionEstimate motion;
  msg::Segmentation segmentation;
  auto cursor = reader.messages({.topics = {dds::kMotionTopic, dds::kSegmentationTopic}});
  mcap::MessageView m;
  while (true) {
    try {
      if (!cursor.next(m)) break;
    } catch (const InputError& e) {
      counts.damage = e.what();
      break;
    }
    const std::string what = path + ": " + m.channel->topic + " message " + std::to_string(m.sequence);
    std::string why;
    if (m.channel->topic == dds::kMotionTopic) {
      from_cdr(motion_type, m.data, m.size, motion, what);
      Stream& s = streams[motion.stream_id().to_string()];
      if (motion.end_of_stream()) {
        // End of stream carries no result; pairs already complete were handed on.
      } else if (auto value = dds::from_msg(motion, why)) {
        s.pairing.add_first(motion.frame_index(), std::move(*value));
      } else {
        ++counts.invalid;
        spdlog::warn("{}: {}", what, why);
      }
      drain(motion.stream_id().to_string(), s);
    } else {
      from_cdr(segmentation_type, m.data, m.size, segmentation, what);
      Stream& s = streams[segmentation.stream_id().to_string()];
      if (segmentation.end_of_stream()) {
        // End of stream carries no result; pairs already complete were handed on.
      } else if (auto value = dds::from_msg(segmentation, why)) {
        s.pairing.add_second(segmentation.frame_index(), std::move(*value));
      } else {
        ++counts.invalid;
        spdlog::warn("{}: {}", what, why);
      }
      drain(segmentation.stream_id().to_string(), s);
    }
  }
  for (auto& [id, s] : streams) counts.unpaired += s.pairing.dropped() + s.pairing.pending();
  return counts;
}

}  // namespace uavmot::record
