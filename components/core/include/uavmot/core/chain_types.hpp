#pragma once
// The data that flows between the three layers of the chain (paper Fig. 1).
// These are plain structs with no DDS dependency; components/dds/convert maps
// them to the IDL types field by field, losslessly, so the in-process chain
// (`uavmot process`) and the distributed chain produce identical results.

#include <cstdint>
#include <string>
#include <vector>

#include <opencv2/core/mat.hpp>
#include <opencv2/core/matx.hpp>
#include <opencv2/core/types.hpp>

#include "uavmot/core/homography.hpp"
#include "uavmot/core/oriented_box.hpp"
#include "uavmot/core/segmentation_method.hpp"

namespace uavmot {

// One image of a stream. Frame indices start at 1 (MOTChallenge).
struct Frame {
  std::string stream_id;
  int64_t index = 0;
  int64_t capture_time_ns = 0;
  cv::Mat image;  // CV_8UC1 (mono8) or CV_8UC3 (bgr8)
};

// A KLT feature in the current frame with its motion relative to the compensated background.
struct TrackedFeature {
  uint64_t id = 0;
  cv::Point2d position;
  cv::Vec2d velocity;           // px/frame, relative to the background
  double velocity_sigma = 0.0;  // px/frame, 1-sigma noise of `velocity`
  uint32_t age = 0;             // frames this feature has been tracked
  bool moving = false;
};

struct HomographyQuality {
  bool valid = false;
  uint32_t inliers = 0;
  double residual_px = 0.0;  // RMS transfer error over inliers
};

// Output of the independent-motion layer for one frame.
struct MotionEstimate {
  std::string stream_id;
  int64_t frame_index = 0;
  int64_t capture_time_ns = 0;
  int image_width = 0;  // size of the frame it was estimated on
  int image_height = 0;
  Homography homography = Homography::eye();  // frame k-1 -> frame k
  HomographyQuality quality;
  std::vector<TrackedFeature> features;
};

struct FeatureCluster {
  uint32_t id = 0;
  OrientedBox box;
  cv::Vec2d velocity;  // mean relative velocity of its features, px/frame
  std::vector<uint64_t> feature_ids;
};

// An object hypothesis: an oriented box from one segmentation method.
struct Region {
  OrientedBox box;
  SegmentationMethod method = SegmentationMethod::Fusion;
  double score = 0.0;
  int32_t cluster_id = -1;  // the cluster it was segmented from, -1 if none
};

struct SegmentationResult {
  std::string stream_id;
  int64_t frame_index = 0;
  int64_t capture_time_ns = 0;
  std::vector<FeatureCluster> clusters;
  std::vector<Region> regions;
};

enum class TrackState : uint8_t { Tentative = 0, Confirmed = 1, Coasting = 2 };

struct Track {
  uint64_t id = 0;  // from 1
  TrackState state = TrackState::Tentative;
  // The tracker rounds box and velocity to float32 (round_to_float32): 6e-5 px at 1000 px, far
  // below the result files' 1/1000 px, and the air -> ground link carries them exactly in 4 bytes.
  OrientedBox box;
  cv::Vec2d velocity;  // px/frame in the current frame, relative to the ground
  // 1-sigma uncertainties from the Kalman covariance.
  double sigma_x = 0.0;
  double sigma_y = 0.0;
  double sigma_width = 0.0;
  double sigma_length = 0.0;
  double sigma_angle_deg = 0.0;
  uint32_t age = 0;                  // frames since the track started
  uint32_t frames_since_update = 0;  // frames coasted on prediction
  std::vector<uint64_t> feature_ids;
};

struct TrackList {
  std::string stream_id;
  int64_t frame_index = 0;
  int64_t capture_time_ns = 0;
  std::vector<Track> tracks;
};

// A track's box and velocity rounded to the nearest float32 values, and whether they are.
void round_to_float32(Track& track);
bool is_float32_exact(const Track& track);

const char* to_string(TrackState state);

}  // namespace uavmot
