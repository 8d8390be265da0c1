#pragma once
// Draws what the chain found on its frame, like the paper's Fig. 6: moving features as yellow
// velocity vectors, feature clusters cyan, regions red, tracks green with id and speed.
// Pure drawing, no DDS; used by `uavmot process --video` and by the `uavmot-view` node.

#include <string>

#include <opencv2/core/mat.hpp>
#include <opencv2/core/types.hpp>

#include "uavmot/core/chain_types.hpp"

namespace uavmot::view {

// Colours in BGR, so tests and docs name the same values.
inline const cv::Scalar kMovingFeatureColour(0, 255, 255);      // yellow
inline const cv::Scalar kStationaryFeatureColour(0, 0, 255);    // red dots
inline const cv::Scalar kClusterColour(255, 255, 0);            // cyan
inline const cv::Scalar kRegionColour(0, 0, 255);               // red
inline const cv::Scalar kConfirmedTrackColour(0, 255, 0);       // green
inline const cv::Scalar kTentativeTrackColour(0, 140, 0);       // dim green, thin
inline const cv::Scalar kCoastingTrackColour(0, 255, 0);        // green, dashed

struct OverlayOptions {
  double gsd_m = 0.0;           // m/px; > 0 labels speeds in km/h, else px/frame
  double fps = 25.0;            // for km/h and the time label
  double scale = 1.0;           // output size / frame size (drawing stays thin and sharp when enlarged)
  double vector_scale = 10.0;   // feature velocity arrows are this many frames long
  bool moving_features = true;
  bool stationary_features = false;
  bool clusters = true;
  bool regions = true;
  bool tracks = true;
  bool tentative_tracks = true;
  bool frame_label = true;
  int line_thickness = 0;       // 0: from the output size (1 px up to ~1000 px tall)
};

// The annotated frame (CV_8UC3, frame size times `scale`). Any of the results may be null.
// Coordinates are OpenCV's continuous frame (docs/conventions.md).
cv::Mat draw_overlay(const cv::Mat& frame, const MotionEstimate* motion, const SegmentationResult* segmentation,
                     const TrackList* tracks, const OverlayOptions& options);

// Speed of a velocity in px/frame for a label: "43 km/h" when gsd_m > 0 (|v| * gsd * fps * 3.6),
// else "1.2 px/f".
std::string format_speed(const cv::Vec2d& velocity_px_per_frame, double gsd_m, double fps);

// "frame 42  1.64 s" (time of frame `index`, counted from frame 1; no time when fps <= 0).
std::string format_frame_label(int64_t index, double fps);

}  // namespace uavmot::view
