#include "uavmot/dds/frame_convert.hpp"

#include <cstring>

#include <opencv2/imgcodecs.hpp>

namespace uavmot::dds {

int channels_of(msg::Encoding encoding) {
  switch (encoding) {
    case msg::Encoding::MONO8: return 1;
    case msg::Encoding::BGR8: return 3;
    case msg::Encoding::JPEG: return 0;
  }
  return -1;
}

msg::Frame to_msg(const Frame& frame) {
  msg::Frame sample;
  sample.stream_id(frame.stream_id);
  sample.frame_index(frame.index);
  sample.capture_time_ns(frame.capture_time_ns);
  sample.width(static_cast<uint32_t>(frame.image.cols));
  sample.height(static_cast<uint32_t>(frame.image.rows));
  sample.encoding(frame.image.channels() == 3 ? msg::Encoding::BGR8 : msg::Encoding::MONO8);
  sample.end_of_stream(false);
  const cv::Mat continuous = frame.image.isContinuous() ? frame.image : frame.image.clone();
  const size_t bytes = continuous.total() * continuous.elemSize();
  sample.data().resize(bytes);
  std::memcpy(sample.data().data(), continuous.data, bytes);
  return sample;
}

msg::Frame to_jpeg_msg(const Frame& frame, int quality) {
  msg::Frame sample;
  sample.stream_id(frame.stream_id);
  sample.frame_index(frame.index);
  sample.capture_time_ns(frame.capture_time_ns);
  sample.width(static_cast<uint32_t>(frame.image.cols));
  sample.height(static_cast<uint32_t>(frame.image.rows));
  sample.encoding(msg::Encoding::JPEG);
  sample.end_of_stream(false);
  cv::imencode(".jpg", frame.image, sample.data(), {cv::IMWRITE_JPEG_QUALITY, quality});
  return sample;
}

msg::Frame end_of_stream_frame(const std::string& stream_id, int64_t last_index) {
  msg::Frame sample;
  sample.stream_id(stream_id);
  sample.frame_index(last_index);
  sample.end_of_stream(true);
  return sample;
}

namespace {

std::optional<Frame> convert(const msg::Frame& sample, std::string& why, uint8_t* view_of) {
  Frame frame;
  frame.stream_id = sample.stream_id().to_string();
  frame.index = sample.frame_index();
  frame.capture_time_ns = sample.capture_time_ns();
  const int channels = channels_of(sample.encoding());
  constexpr uint32_t kMaxSide = 16384;
  if (sample.width() == 0 || sample.height() == 0 || sample.width() > kMaxSide || sample.height() > kMaxSide) {
    why = "frame size " + std::to_string(sample.width()) + "x" + std::to_string(sample.height()) + " out of range";
    return std::nullopt;
  }
  if (frame.index < 1) {
    why = "frame index " + std::to_string(frame.index) + " < 1";
    return std::nullopt;
  }
  if (channels < 0) {
    why = "unknown encoding";
    return std::nullopt;
  }
  if (channels == 0) {  // JPEG
    // imdecode asserts (throws cv::Exception) on an empty buffer and on some corrupt streams.
    try {
      if (!sample.data().empty()) frame.image = cv::imdecode(sample.data(), cv::IMREAD_UNCHANGED);
    } catch (const cv::Exception&) {
      frame.image.release();
    }
    if (frame.image.empty() || frame.image.cols != static_cast<int>(sample.width()) ||
        frame.image.rows != static_cast<int>(sample.height())) {
      why = "JPEG payload does not decode to the announced size";
      return std::nullopt;
    }
    if (frame.image.type() != CV_8UC1 && frame.image.type() != CV_8UC3) {  // the chain takes mono8 or bgr8
      why = "JPEG payload decodes to an image that is neither mono8 nor bgr8";
      return std::nullopt;
    }
    return frame;
  }
  const size_t expected = static_cast<size_t>(sample.width()) * sample.height() * static_cast<size_t>(channels);
  if (sample.data().size() != expected) {
    why = "payload of " + std::to_string(sample.data().size()) + " bytes, expected " + std::to_string(expected) +
          " for " + std::to_string(sample.width()) + "x" + std::to_string(sample.height()) + "x" + std::to_string(channels);
    return std::nullopt;
  }
  const int type = channels == 3 ? CV_8UC3 : CV_8UC1;
  if (view_of) {
    frame.image = cv::Mat(static_cast<int>(sample.height()), static_cast<int>(sample.width()), type, view_of);
    return frame;
  }
  frame.image.create(static_cast<int>(sample.height()), static_cast<int>(sample.width()), type);
  std::memcpy(frame.image.data, sample.data().data(), expected);
  return frame;
}

}  // namespace

std::optional<Frame> from_msg(const msg::Frame& sample, std::string& why) { return convert(sample, why, nullptr); }

std::optional<Frame> view_msg(msg::Frame& sample, std::string& why) { return convert(sample, why, sample.data().data()); }

}  // namespace uavmot::dds
