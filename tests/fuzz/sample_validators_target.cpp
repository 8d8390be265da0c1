// Fuzz target: arbitrary bytes as a CDR sample of each chain topic, the downlink's results and the
// tracker state, then the receive-side validation. Whatever arrives on the wire (or sits in a
// tracker state file), deserialization and validation may reject it but must not crash; a tracker
// state that passes is restored and run for a frame, as a respawned tracking node does.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include "fuzz_targets.hpp"
#include "downlinkPubSubTypes.h"
#include "framePubSubTypes.h"
#include "motionPubSubTypes.h"
#include "segmentationPubSubTypes.h"
#include "tracker_statePubSubTypes.h"
#include "tracker_state_io.hpp"
#include "tracksPubSubTypes.h"
#include "uavmot/core/error.hpp"
#include "uavmot/dds/cdr_sample.hpp"
#include "uavmot/dds/chain_convert.hpp"
#include "uavmot/dds/downlink_convert.hpp"
#include "uavmot/dds/frame_convert.hpp"
#include "uavmot/tracking/tracker.hpp"

namespace {

template <class PubSubType>
std::optional<typename PubSubType::type> deserialize(const uint8_t* data, size_t size) {
  PubSubType type;
  typename PubSubType::type sample;
  try {
    uavmot::dds::from_cdr(type, data, size, sample, "fuzz input");
  } catch (const uavmot::InputError&) {
    return std::nullopt;  // what a reader drops
  }
  return sample;
}

template <class PubSubType>
void check(const uint8_t* data, size_t size) {
  if (auto sample = deserialize<PubSubType>(data, size)) {
    std::string why;
    (void)uavmot::dds::from_msg(*sample, why);
  }
}

// As the tracking node on start: decode, restore (which refuses an inconsistent state), track a frame.
void check_tracker_state(const uint8_t* data, size_t size) {
  using namespace uavmot;
  auto snapshot = deserialize<msg::TrackerSnapshotPubSubType>(data, size);
  if (!snapshot) return;
  std::string why;
  auto state = tracking::from_msg(*snapshot, why);
  if (!state) return;
  tracking::Tracker tracker(tracking::TrackerOptions{}, SceneInfo{});
  try {
    tracker.restore(*state);
  } catch (const InvalidArgument&) {
    return;
  }
  MotionEstimate motion;
  motion.frame_index = snapshot->frame_index() + 1;
  motion.image_width = 640;
  motion.image_height = 480;
  motion.quality.valid = true;
  SegmentationResult segmentation;
  segmentation.frame_index = motion.frame_index;
  (void)tracker.process(motion, segmentation);
}

}  // namespace

namespace uavmot::fuzz {

int sample_validators(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  switch (data[0] % 6) {
    case 0: check<uavmot::msg::FramePubSubType>(data + 1, size - 1); break;
    case 1: check<uavmot::msg::MotionEstimatePubSubType>(data + 1, size - 1); break;
    case 2: check<uavmot::msg::SegmentationPubSubType>(data + 1, size - 1); break;
    case 3: check<uavmot::msg::TrackListPubSubType>(data + 1, size - 1); break;
    case 4: check<uavmot::msg::FrameResultsPubSubType>(data + 1, size - 1); break;
    default: check_tracker_state(data + 1, size - 1); break;
  }
  return 0;
}

}  // namespace uavmot::fuzz
