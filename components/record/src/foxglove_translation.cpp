#include "uavmot/record/foxglove_translation.hpp"

#include "uavmot/dds/chain_convert.hpp"
#include "uavmot/dds/downlink_convert.hpp"
#include "uavmot/dds/frame_convert.hpp"
#include "uavmot/dds/topics.hpp"
#include "uavmot/foxglove/encode.hpp"
#include "uavmot/foxglove/schemas.hpp"

namespace uavmot::record {

std::optional<FoxgloveChannelSpec> foxglove_channel(const std::string& topic, const FoxgloveOptions& options) {
  const char* image_schema =
      options.image_format == foxglove::ImageFormat::Jpeg ? foxglove::kCompressedImageSchema : foxglove::kRawImageSchema;
  if (topic == dds::kFramesTopic) return FoxgloveChannelSpec{"uavmot/foxglove/image", image_schema};
  if (topic == dds::kDownlinkPreviewTopic) return FoxgloveChannelSpec{"uavmot/foxglove/downlink/preview", image_schema};
  if (topic == dds::kDownlinkResultsTopic) {
    return FoxgloveChannelSpec{"uavmot/foxglove/downlink/results", foxglove::kImageAnnotationsSchema};
  }
  if (topic == dds::kMotionTopic) return FoxgloveChannelSpec{"uavmot/foxglove/features", foxglove::kImageAnnotationsSchema};
  if (topic == dds::kSegmentationTopic) return FoxgloveChannelSpec{"uavmot/foxglove/regions", foxglove::kImageAnnotationsSchema};
  if (topic == dds::kTracksTopic) return FoxgloveChannelSpec{"uavmot/foxglove/tracks", foxglove::kImageAnnotationsSchema};
  return std::nullopt;
}

std::optional<std::vector<uint8_t>> to_foxglove(msg::Frame& sample, const FoxgloveOptions& options, std::string& why) {
  why.clear();
  if (sample.end_of_stream()) return std::nullopt;
  // A JPEG frame (e.g. the downlink preview) goes out as it came: no decode, no re-encode.
  if (sample.encoding() == msg::Encoding::JPEG && options.image_format == foxglove::ImageFormat::Jpeg) {
    return foxglove::encode(foxglove::jpeg_image(sample.stream_id().to_string(), sample.capture_time_ns(), sample.data()));
  }
  // Raw pixels are viewed in place (no copy) unless they must be decoded.
  auto frame = sample.encoding() == msg::Encoding::JPEG ? dds::from_msg(sample, why) : dds::view_msg(sample, why);
  if (!frame) return std::nullopt;
  if (options.image_format == foxglove::ImageFormat::Raw) return foxglove::encode(foxglove::raw_image(*frame));
  return foxglove::encode(foxglove::jpeg_image(*frame, options.jpeg_quality));
}

std::optional<std::vector<uint8_t>> to_foxglove(msg::MotionEstimate& sample, const FoxgloveOptions& options, std::string& why) {
  why.clear();
  if (sample.end_of_stream()) return std::nullopt;
  const auto motion = dds::from_msg(sample, why);
  if (!motion) return std::nullopt;
  return foxglove::encode(foxglove::annotate_motion(*motion, options.style));
}

std::optional<std::vector<uint8_t>> to_foxglove(msg::Segmentation& sample, const FoxgloveOptions&, std::string& why) {
  why.clear();
  if (sample.end_of_stream()) return std::nullopt;
  const auto segmentation = dds::from_msg(sample, why);
  if (!segmentation) return std::nullopt;
  return foxglove::encode(foxglove::annotate_segmentation(*segmentation));
}

std::optional<std::vector<uint8_t>> to_foxglove(msg::TrackList& sample, const FoxgloveOptions& options, std::string& why) {
  why.clear();
  if (sample.end_of_stream()) return std::nullopt;
  const auto tracks = dds::from_msg(sample, why);
  if (!tracks) return std::nullopt;
  return foxglove::encode(foxglove::annotate_tracks(*tracks, options.style));
}

std::optional<std::vector<uint8_t>> to_foxglove(msg::ComponentHealth&, const FoxgloveOptions&, std::string& why) {
  why.clear();
  return std::nullopt;
}

std::optional<std::vector<uint8_t>> to_foxglove(msg::FrameResults& sample, const FoxgloveOptions& options, std::string& why) {
  why.clear();
  if (sample.end_of_stream()) return std::nullopt;
  const auto ground = dds::from_msg(sample, why);
  if (!ground) return std::nullopt;
  foxglove::ImageAnnotations out;
  if (ground->regions) out = foxglove::annotate_printed_regions(*ground->regions, sample.capture_time_ns());
  if (ground->tracks) {
    auto tracks = foxglove::annotate_tracks(*ground->tracks, options.style);
    for (auto& p : tracks.points) out.points.push_back(std::move(p));
    for (auto& t : tracks.texts) out.texts.push_back(std::move(t));
  }
  return foxglove::encode(out);
}

}  // namespace uavmot::record
