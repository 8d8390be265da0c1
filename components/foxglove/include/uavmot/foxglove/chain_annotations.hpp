#pragma once
// The chain's results as Foxglove messages, drawn like the paper's Fig. 6 (and uavmot-view, with
// the same colours): moving features yellow with velocity vectors, clusters cyan, regions red,
// tracks green with "#id speed" labels. One ImageAnnotations message per result sample, stamped
// with its frame's capture time, so Foxglove's Image panel lays it over the matching image.
// No DDS: record and the live bridge convert the samples they receive with these functions.

#include <optional>
#include <string>

#include "uavmot/core/chain_types.hpp"
#include "uavmot/core/result_files.hpp"
#include "uavmot/foxglove/messages.hpp"

namespace uavmot::foxglove {

struct AnnotationStyle {
  double gsd_m = 0.0;          // m/px; > 0 labels speeds in km/h, else px/frame
  double fps = 25.0;           // for km/h
  double vector_scale = 10.0;  // feature velocity vectors are this many frames long
  bool tentative_tracks = true;
  bool stationary_features = false;
};

// Tracks: oriented box as a closed polygon (green; tentative dim, coasting thin), "#id speed" text.
ImageAnnotations annotate_tracks(const TrackList& tracks, const AnnotationStyle& style);
// Regions (red polygons) and feature clusters (cyan polygons).
ImageAnnotations annotate_segmentation(const SegmentationResult& segmentation);
// Moving features: yellow points and one velocity vector each (a line list); stationary ones as
// red points when asked.
ImageAnnotations annotate_motion(const MotionEstimate& motion, const AnnotationStyle& style);

// Regions as the downlink carries them (axis-aligned, thousandths of a pixel: core's
// PrintedRegion) as red rectangles, stamped with the frame's capture time.
ImageAnnotations annotate_printed_regions(const std::vector<PrintedRegion>& regions, int64_t capture_time_ns);

enum class ImageFormat { Jpeg, Raw };
ImageFormat parse_image_format(const std::string& name);  // "jpeg" | "raw"; throws InvalidArgument
const char* to_string(ImageFormat format);

// A mono8 or bgr8 frame as a RawImage (pixels copied row by row, no padding).
RawImage raw_image(const Frame& frame);
// A frame as a JPEG CompressedImage (encoded at `quality`).
CompressedImage jpeg_image(const Frame& frame, int quality);
// JPEG bytes the chain already carries (a JPEG-encoded frame) as a CompressedImage, not re-encoded.
CompressedImage jpeg_image(const std::string& stream_id, int64_t capture_time_ns, std::vector<uint8_t> jpeg);

}  // namespace uavmot::foxglove
