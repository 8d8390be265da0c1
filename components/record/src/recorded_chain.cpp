#include "uavmot/record/recorded_chain.hpp"

#include <map>
#include <set>

#include <spdlog/spdlog.h>

#include "motionPubSubTypes.h"
#include "segmentationPubSubTypes.h"
#include "tracksPubSubTypes.h"
#include "uavmot/core/error.hpp"
#include "uavmot/core/frame_pairing.hpp"
#include "uavmot/dds/chain_convert.hpp"
#include "uavmot/dds/topics.hpp"
#include "uavmot/mcap/reader.hpp"
#include "uavmot/dds/cdr_sample.hpp"

namespace uavmot::record {
namespace {

// One topic: decode the CDR payload, skip end-of-stream markers, validate, hand on.
template <class PubSubType>
class TopicDecoder {
 public:
  template <class Handler>
  bool decode(const mcap::MessageView& m, const std::string& what, RecordedSampleCounts& counts, uint64_t& handed,
              const Handler& handler) {
    dds::from_cdr(type_, m.data, m.size, sample_, what);
    if (sample_.end_of_stream()) return false;  // carries no result
    std::string why;
    auto value = dds::from_msg(sample_, why);
    if (!value) {
      ++counts.invalid;
      spdlog::warn("{}: {}", what, why);
      return false;
    }
    handler(*value);
    ++handed;
    return true;
  }

 private:
  PubSubType type_;
  typename PubSubType::type sample_;
};

}  // namespace

RecordedSampleCounts read_recorded_samples(const std::string& path, const RecordedSampleHandlers& handlers) {
  mcap::Reader reader;
  reader.open(path);
  std::set<std::string> wanted;
  if (handlers.motion) wanted.insert(dds::kMotionTopic);
  if (handlers.segmentation) wanted.insert(dds::kSegmentationTopic);
  if (handlers.tracks) wanted.insert(dds::kTracksTopic);
  std::set<std::string> present;
  for (const auto& [id, channel] : reader.channels()) present.insert(channel.topic);
  for (const auto& topic : wanted) {
    if (!present.count(topic)) throw InputError(path + ": the recording has no " + topic + " topic");
  }

  RecordedSampleCounts counts;
  TopicDecoder<msg::MotionEstimatePubSubType> motion;
  TopicDecoder<msg::SegmentationPubSubType> segmentation;
  TopicDecoder<msg::TrackListPubSubType> tracks;
  auto cursor = reader.messages({.topics = wanted});
  mcap::MessageView m;
  while (true) {
    try {
      if (!cursor.next(m)) break;
    } catch (const InputError& e) {
      counts.damage = e.what();
      break;
    }
    const std::string what = path + ": " + m.channel->topic + " message " + std::to_string(m.sequence);
    if (m.channel->topic == dds::kMotionTopic) {
      motion.decode(m, what, counts, counts.motion, handlers.motion);
    } else if (m.channel->topic == dds::kSegmentationTopic) {
      segmentation.decode(m, what, counts, counts.segmentation, handlers.segmentation);
    } else {
      tracks.decode(m, what, counts, counts.tracks, handlers.tracks);
    }
  }
  return counts;
}

RecordedChainCounts read_recorded_chain(const std::string& path, const RecordedPairHandler& handle) {
  std::map<std::string, FramePairing<MotionEstimate, SegmentationResult>> streams;
  RecordedChainCounts counts;
  auto drain = [&](const std::string& id) {
    while (auto pair = streams[id].pop()) {
      handle(id, pair->first, pair->second);
      ++counts.pairs;
    }
  };
  RecordedSampleHandlers handlers;
  handlers.motion = [&](const MotionEstimate& m) {
    streams[m.stream_id].add_first(m.frame_index, m);
    drain(m.stream_id);
  };
  handlers.segmentation = [&](const SegmentationResult& s) {
    streams[s.stream_id].add_second(s.frame_index, s);
    drain(s.stream_id);
  };
  try {
    const auto samples = read_recorded_samples(path, handlers);
    counts.invalid = samples.invalid;
    counts.damage = samples.damage;
  } catch (const InputError& e) {
    const std::string message = e.what();
    if (message.find(": the recording has no ") == std::string::npos) throw;
    throw InputError(message + "; re-running tracking needs both uavmot/motion and uavmot/segmentation");
  }
  for (auto& [id, s] : streams) counts.unpaired += s.dropped() + s.pending();
  return counts;
}

}  // namespace uavmot::record
