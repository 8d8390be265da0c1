#pragma once
// The downlink's results: motion, segmentation and tracks from the UAV's own domain, joined by
// frame, out as one compact sample per frame on the link (uavmot/downlink/results, idl/downlink.idl).
// A frame goes once its motion, segmentation and tracks are all there; a frame the chain skipped a
// part of (live mode) goes with what it has when a later frame is complete. A stream's end goes
// after all three inputs ended.

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "downlinkPubSubTypes.h"
#include "motionPubSubTypes.h"
#include "segmentationPubSubTypes.h"
#include "tracksPubSubTypes.h"
#include "uavmot/dds/downlink_convert.hpp"
#include "uavmot/dds/health_reporter.hpp"
#include "uavmot/dds/node_support.hpp"
#include "uavmot/dds/participant.hpp"

namespace uavmot::downlink {

class ResultsRelay {
 public:
  // `resume`: read the chain topics with their writers' recent history (dds::TopicClass::ChainResume).
  // `stream_ids`: relay only these (a content filter: other ids never take one of the readers'
  // instance slots, docs/topics.md "Instance limits"); empty: every id.
  ResultsRelay(dds::Participant& air, dds::Participant& link, int required_readers, dds::HealthReporter& health,
               bool resume = false, const std::vector<std::string>& stream_ids = {});

  // Takes what waits on the three inputs and publishes every frame that is complete. True if any was taken.
  bool pump();

  int streams_ended() const { return streams_ended_; }
  const dds::DownlinkDrops& drops() const { return drops_; }
  dds::TopicWriter<msg::FrameResultsPubSubType>& writer() { return *writer_; }
  dds::TopicReader<msg::TrackListPubSubType>& tracks() { return *tracks_; }
  // Writers matched on the three inputs (dds/upstream_watch.hpp).
  int writers_matched() const { return motion_->matched() + segmentation_->matched() + tracks_->matched(); }

  // Logs when the link's reader comes and goes (the link dropped, the ground restarted).
  void log_link_changes();

 private:
  struct StreamState {
    std::map<int64_t, dds::FrameParts> pending;
    int ended_inputs = 0;  // of motion, segmentation, tracks
    int64_t last_index = 0;
  };

  template <class Reader, class Part>
  bool take(Reader& reader, std::optional<Part> dds::FrameParts::*part);
  void publish_up_to(const std::string& id, StreamState& s, int64_t index);
  void end(const std::string& id, StreamState& s);

  dds::DeliveryMode mode_;
  std::unique_ptr<dds::TopicReader<msg::MotionEstimatePubSubType>> motion_;
  std::unique_ptr<dds::TopicReader<msg::SegmentationPubSubType>> segmentation_;
  std::unique_ptr<dds::TopicReader<msg::TrackListPubSubType>> tracks_;
  std::unique_ptr<dds::TopicWriter<msg::FrameResultsPubSubType>> writer_;
  dds::HealthReporter& health_;
  dds::RejectLog rejects_;
  std::map<std::string, StreamState> streams_;
  int streams_ended_ = 0;
  dds::DownlinkDrops drops_;
  int matched_ = 0;
};

}  // namespace uavmot::downlink
