#pragma once
// The object segmentation layer (paper section III): moving features -> clusters -> regions.
//
// The gradient segmentations need pixels only in a window around each cluster, so the segmenter
// works from image crops. The whole-frame entry point builds those crops from the frame and
// takes the same path, so both give identical results:
//
//   Segmenter segmenter(options, scene);
//   SegmentationResult r = segmenter.process(frame, motion);          // in-process chain
//
//   // split deployment: the side with the frames cuts the crops, the other side segments
//   auto rois = segmenter.required_crops(motion, frame.image.size());
//   SegmentationInput input = make_segmentation_input(frame, rois);  // ship input.crops
//   SegmentationResult r = segmenter.process(input, motion);

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core/mat.hpp>
#include <opencv2/core/types.hpp>

#include "uavmot/core/chain_types.hpp"
#include "uavmot/core/scene_info.hpp"
#include "uavmot/segmentation/feature_clustering.hpp"
#include "uavmot/segmentation/segmentation_options.hpp"
#include "uavmot/segmentation/shadow_offset.hpp"

namespace uavmot::segmentation {

// A rectangle of a frame: `pixels` (CV_8UC1 or CV_8UC3, size == roi.size()) cut at `roi`.
struct ImageCrop {
  cv::Rect roi;
  cv::Mat pixels;
};

// The pixels the segmenter needs for one frame instead of the whole frame.
struct SegmentationInput {
  std::string stream_id;
  int64_t frame_index = 0;
  int64_t capture_time_ns = 0;
  cv::Size image_size;  // of the full frame; features outside it are skipped
  std::vector<ImageCrop> crops;
};

// Crops of `frame` at `rois` (clipped to the frame; empty ones dropped). The crops share the
// frame's pixels (no copy).
SegmentationInput make_segmentation_input(const Frame& frame, const std::vector<cv::Rect>& rois);

// What the last process() call skipped or degraded, for health reporting.
struct SegmentationStats {
  ClusteringStats clustering;
  size_t windows = 0;                 // cluster windows segmented
  size_t windows_without_pixels = 0;  // no usable crop covered the window
  size_t invalid_crops = 0;           // crop with empty pixels, wrong type or size != roi
  size_t fallback_regions = 0;        // feature boxes added where the gradients found nothing
  size_t duplicate_regions = 0;       // regions dropped as duplicates of an earlier one
  size_t static_regions = 0;          // regions dropped by the shift check (static texture)
  size_t evidence_moves = 0;          // regions moved onto their motion evidence
  size_t evidence_fallbacks = 0;      // blob-less clusters given a box on their motion evidence
  std::optional<cv::Vec2d> shadow_offset_px;  // the shadow offset the regions were corrected by, if any
};

class Segmenter {
 public:
  // Throws InvalidArgument for invalid options or scene (non-positive GSD, fps or vehicle size).
  Segmenter(SegmentationOptions options, SceneInfo scene);

  // Whole-frame path: cuts the crops the motion estimate needs and segments them.
  SegmentationResult process(const Frame& frame, const MotionEstimate& motion);
  // Crop path. Result ids (stream, frame index, time) are the motion estimate's.
  SegmentationResult process(const SegmentationInput& input, const MotionEstimate& motion);

  // Image windows (clipped to image_size) the gradient segmentations will read for this
  // motion estimate: one per cluster, none for method=clustering.
  std::vector<cv::Rect> required_crops(const MotionEstimate& motion, cv::Size image_size) const;

  const SegmentationOptions& options() const { return options_; }
  const SceneInfo& scene() const { return scene_; }
  const SegmentationStats& last_stats() const { return stats_; }

  // What the next frame depends on: the grey cluster windows of the frame segmented last (the shift
  // check's previous frame). A new process that restore_state()s these bytes segments the next frame
  // as this one would have; without them its shift check is skipped for that frame, which can keep a
  // region of static texture that this one dropped. restore_state() throws InputError for bytes it
  // refuses (another format, damaged).
  std::vector<uint8_t> save_state() const;
  void restore_state(const std::vector<uint8_t>& bytes);
  // The stream and frame segmented last, -1 before any.
  const std::string& last_stream_id() const { return previous_stream_; }
  int64_t last_frame_index() const { return previous_frame_; }

 private:
  std::vector<FeatureCluster> cluster(const MotionEstimate& motion, cv::Size image_size, ClusteringStats* stats) const;
  cv::Rect window_of(const FeatureCluster& cluster, cv::Size image_size) const;
  // How far past each end of a blob-less cluster's box its motion evidence is searched (px).
  double evidence_lengthen_px() const;
  // A cluster's window (window_of) with room around it for that search: the crop the segmenter
  // needs and keeps for the next frame's shift check. The window itself when that fallback is off.
  cv::Rect evidence_window_of(const cv::Rect& window, cv::Size image_size) const;
  cv::Mat accumulator(const cv::Mat& gray) const;
  cv::Mat normalised_accumulator(SegmentationMethod method, const cv::Mat& gray) const;
  // A box (method=clustering) around the cluster's features that no region explains, when there
  // are enough of them to be an object the gradients missed.
  std::optional<Region> uncovered_features_region(const FeatureCluster& cluster,
                                                  const std::vector<cv::Point2d>& feature_positions,
                                                  const std::vector<Region>& regions) const;
  // No longer and no wider than the largest region a blob may give (max_length_factor and
  // max_width_factor times the scene's vehicle).
  bool within_vehicle_size(const OrientedBox& box) const;
  std::vector<Region> segment_window(const cv::Mat& gray, const cv::Rect& window, const FeatureCluster& cluster,
                                     const std::vector<cv::Point2d>& feature_positions) const;

  SegmentationOptions options_;
  SceneInfo scene_;
  // Accumulator response to a step of regions.min_edge_contrast grey levels, per gradient method.
  std::array<double, kSegmentationMethods.size()> references_;
  SegmentationStats stats_;
  // The grey cluster windows of the frame segmented last, for the shift check of the next.
  std::string previous_stream_;
  int64_t previous_frame_ = -1;
  std::vector<ImageCrop> previous_windows_;
  ShadowOffset shadow_;
};

}  // namespace uavmot::segmentation
