#pragma once
// Chain types <-> IDL samples, field by field and lossless (doubles stay doubles), so the
// distributed chain computes exactly what `uavmot process` computes. Received samples are
// validated (finite numbers, bounded sequences, sane boxes) before use.

#include <optional>
#include <string>

#include "motion.h"
#include "segmentation.h"
#include "tracks.h"
#include "uavmot/core/chain_types.hpp"

namespace uavmot::dds {

// Bounds that no real sample reaches; anything beyond is garbage on the wire.
inline constexpr size_t kMaxFeatures = 100000;
inline constexpr size_t kMaxClusters = 10000;
inline constexpr size_t kMaxRegions = 10000;
inline constexpr size_t kMaxTracks = 10000;
inline constexpr size_t kMaxIdsPerObject = 10000;

msg::MotionEstimate to_msg(const MotionEstimate& motion);
msg::Segmentation to_msg(const SegmentationResult& segmentation);
msg::TrackList to_msg(const TrackList& tracks);

// nullopt with `why` set when the sample is malformed.
std::optional<MotionEstimate> from_msg(const msg::MotionEstimate& sample, std::string& why);
std::optional<SegmentationResult> from_msg(const msg::Segmentation& sample, std::string& why);
std::optional<TrackList> from_msg(const msg::TrackList& sample, std::string& why);

}  // namespace uavmot::dds
