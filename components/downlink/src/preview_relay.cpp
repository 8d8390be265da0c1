#include "uavmot/downlink/preview_relay.hpp"

#include <algorithm>

#include <opencv2/imgproc.hpp>

#include "uavmot/dds/frame_convert.hpp"

namespace uavmot::downlink {
namespace {

std::chrono::steady_clock::duration seconds(double s) {
  return std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(s));
}

}  // namespace

PreviewRelay::PreviewRelay(dds::Participant& air, dds::Participant& link, const PreviewOptions& o,
                           const std::vector<std::string>& stream_ids)
    : options_(o),
      frames_(air.make_reader<msg::FramePubSubType>(dds::kFramesTopic, dds::TopicClass::Preview, stream_ids)),
      writer_(link.make_writer<msg::FramePubSubType>(dds::kDownlinkPreviewTopic, dds::TopicClass::Preview,
                                                     o.kbps > 0 ? kFlow : "")) {}

void PreviewRelay::pump(dds::HealthReporter& health) {
  using Clock = std::chrono::steady_clock;
  msg::Frame sample;
  while (frames_->take(sample)) {
    const auto now = Clock::now();
    if (sample.end_of_stream() || now < next_due_) continue;
    next_due_ = now + seconds(1.0 / options_.rate_hz);
    ++due_;
    if (now < share_free_) continue;  // the last image still needs the share
    std::string why;
    auto frame = dds::from_msg(sample, why);
    if (!frame) {
      health.invalid_sample();
      continue;
    }
    if (frame->image.cols > options_.width) {
      const int height = std::max(1, frame->image.rows * options_.width / frame->image.cols);
      cv::resize(frame->image, frame->image, cv::Size(options_.width, height), 0, 0, cv::INTER_AREA);
    }
    auto jpeg = dds::to_jpeg_msg(*frame, options_.quality);
    if (options_.kbps > 0) share_free_ = now + seconds(static_cast<double>(jpeg.data().size()) * 8.0 / (options_.kbps * 1000.0));
    writer_->write(jpeg);
  }
}

}  // namespace uavmot::downlink
