#pragma once
// uavmot samples as Foxglove schema messages (components/foxglove): which Foxglove channel each
// uavmot topic feeds, and the CDR payload for each received sample. Shared by `uavmot record`
// (Foxglove channels beside uavmot's) and `uavmot foxglove` (the live bridge).
//   uavmot/frames       -> uavmot/foxglove/image     foxglove::CompressedImage (jpeg) or RawImage (raw)
//   uavmot/motion       -> uavmot/foxglove/features  foxglove::ImageAnnotations
//   uavmot/segmentation -> uavmot/foxglove/regions   foxglove::ImageAnnotations
//   uavmot/tracks       -> uavmot/foxglove/tracks    foxglove::ImageAnnotations
//   uavmot/health       -> (none: plot it from the uavmot type)
// and on the ground station, from the air -> ground link (`uavmot foxglove --downlink`):
//   uavmot/downlink/preview -> uavmot/foxglove/downlink/preview  CompressedImage (the JPEG as sent) or RawImage
//   uavmot/downlink/results -> uavmot/foxglove/downlink/results  ImageAnnotations: tracks and regions

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "downlink.h"
#include "frame.h"
#include "health.h"
#include "motion.h"
#include "segmentation.h"
#include "tracks.h"
#include "uavmot/foxglove/chain_annotations.hpp"

namespace uavmot::record {

struct FoxgloveOptions {
  foxglove::ImageFormat image_format = foxglove::ImageFormat::Jpeg;
  int jpeg_quality = 80;
  foxglove::AnnotationStyle style;
};

struct FoxgloveChannelSpec {
  std::string topic;        // "uavmot/foxglove/tracks"
  std::string schema_name;  // "foxglove::ImageAnnotations"
};

// The Foxglove channel the uavmot topic feeds, or nullopt (health, unknown topics).
std::optional<FoxgloveChannelSpec> foxglove_channel(const std::string& uavmot_topic, const FoxgloveOptions& options);

// The Foxglove message of one sample as CDR, or nullopt for an end-of-stream marker or a sample
// the chain's validation rejects (`why` then says why; empty for end of stream).
std::optional<std::vector<uint8_t>> to_foxglove(msg::Frame& sample, const FoxgloveOptions& options, std::string& why);
std::optional<std::vector<uint8_t>> to_foxglove(msg::MotionEstimate& sample, const FoxgloveOptions& options, std::string& why);
std::optional<std::vector<uint8_t>> to_foxglove(msg::Segmentation& sample, const FoxgloveOptions& options, std::string& why);
std::optional<std::vector<uint8_t>> to_foxglove(msg::TrackList& sample, const FoxgloveOptions& options, std::string& why);
std::optional<std::vector<uint8_t>> to_foxglove(msg::ComponentHealth& sample, const FoxgloveOptions& options, std::string& why);
std::optional<std::vector<uint8_t>> to_foxglove(msg::FrameResults& sample, const FoxgloveOptions& options, std::string& why);

}  // namespace uavmot::record
