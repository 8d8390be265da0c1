#pragma once
// Local feature clustering (paper III-A): single-linkage clustering of the moving features over
// position and relative velocity, thresholds derived from the GSD and the expected vehicle size.

#include <cstddef>
#include <vector>

#include <opencv2/core/types.hpp>

#include "uavmot/core/chain_types.hpp"
#include "uavmot/core/scene_info.hpp"
#include "uavmot/segmentation/segmentation_options.hpp"

namespace uavmot::segmentation {

// The clustering thresholds in image units for one scene.
struct LinkThresholds {
  double distance_px = 0.0;
  double velocity_px_per_frame = 0.0;
};
LinkThresholds link_thresholds(const ClusteringOptions& options, const SceneInfo& scene);

// What was left out of clustering and why (bad input is skipped and counted, never fatal).
struct ClusteringStats {
  size_t moving_features = 0;      // features with `moving` set
  size_t skipped_non_finite = 0;   // NaN/inf position or velocity
  size_t skipped_outside = 0;      // position outside the image (checked when its size is known)
  size_t dropped_small_clusters = 0;
};

// Clusters the moving features. Ids are 1..n in the order of each cluster's smallest feature id
// (features keep their ids across frames, so the order is stable from frame to frame).
// `image_size` empty disables the outside-the-image check.
std::vector<FeatureCluster> cluster_moving_features(const std::vector<TrackedFeature>& features,
                                                    const ClusteringOptions& options, const SceneInfo& scene,
                                                    cv::Size image_size, ClusteringStats* stats = nullptr);

// The box of a group of feature positions: length axis along the mean velocity (vehicles move
// along their length; falls back to the points' own minimum-area rectangle when not moving),
// extent of the points along and across it, grown symmetrically to at least
// min_length_px x min_width_px (a plausible vehicle footprint).
OrientedBox box_around_features(const std::vector<cv::Point2d>& points, const cv::Vec2d& mean_velocity,
                                double min_length_px, double min_width_px);

}  // namespace uavmot::segmentation
