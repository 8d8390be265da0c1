#pragma once
// The downlink's preview: every 1/rate s, the newest frame as a small JPEG on the link
// (uavmot/downlink/preview), but never faster than its share lets an image through: a newer image
// would replace the one the flow controller is still sending (newest only), and none would ever
// arrive. Frames due while the previous image still uses the share are skipped: the preview gives
// way; the flow controller is the hard cap. When the link is short of bandwidth it is the preview
// that loses images, never the results.

#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "framePubSubTypes.h"
#include "uavmot/dds/health_reporter.hpp"
#include "uavmot/dds/participant.hpp"

namespace uavmot::downlink {

struct PreviewOptions {
  double rate_hz = 0.0;  // 0: no preview
  int width = 320;       // px; the height keeps the aspect ratio
  int quality = 75;      // JPEG
  double kbps = 500.0;   // flow controller limit; 0: none
};

class PreviewRelay {
 public:
  static constexpr const char* kFlow = "uavmot_preview";  // the flow controller's name in the link's participant

  // `stream_ids`: the frames of these only (a content filter, as ResultsRelay's); empty: every id.
  PreviewRelay(dds::Participant& air, dds::Participant& link, const PreviewOptions& options,
               const std::vector<std::string>& stream_ids = {});

  void pump(dds::HealthReporter& health);

  uint64_t due() const { return due_; }
  dds::TopicReader<msg::FramePubSubType>& frames() { return *frames_; }
  dds::TopicWriter<msg::FramePubSubType>& writer() { return *writer_; }

 private:
  PreviewOptions options_;
  std::unique_ptr<dds::TopicReader<msg::FramePubSubType>> frames_;
  std::unique_ptr<dds::TopicWriter<msg::FramePubSubType>> writer_;
  std::chrono::steady_clock::time_point next_due_{}, share_free_{};
  uint64_t due_ = 0;
};

}  // namespace uavmot::downlink
