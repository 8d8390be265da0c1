#pragma once
// Synthetic measurement sequences with known truth for the tracker's tests and benchmark: objects
// move on known ground trajectories, a camera maps the ground to each image (translating, rotating,
// zooming), features are sampled on the objects with small noise, regions are the true boxes plus noise.
// Everything is seeded, so a sequence is the same on every run.

#include <functional>
#include <map>
#include <random>
#include <set>
#include <vector>

#include "uavmot/core/chain_types.hpp"
#include "uavmot/tracking/tracker.hpp"

namespace uavmot::tracking::testing {

struct ObjectPath {
  uint64_t truth_id = 0;
  double length = 15.0;  // px on the ground plane (frame-1 image scale)
  double width = 5.0;
  std::function<cv::Point2d(int)> ground_centre;  // frame -> ground position
  std::function<double(int)> heading_deg;         // optional: default follows the direction of motion
  int feature_count = 10;
};

struct SceneOptions {
  int image_width = 640;
  int image_height = 480;
  double region_centre_noise_px = 0.5;
  double region_size_noise_px = 0.4;
  double region_angle_noise_deg = 2.0;
  double feature_position_noise_px = 0.1;
  double feature_velocity_noise = 0.05;
  double moving_speed_px = 0.15;  // slower objects produce no region and no moving features
  bool merge_close_objects = false;  // objects closer than merge_gap_px give one region
  double merge_gap_px = 1.5;
  int static_features = 20;
  double region_miss_probability = 0.0;  // a moving object's region is dropped this often
  int clutter_regions_per_frame = 0;     // false regions at random places (no features)
  uint32_t seed = 1;
};

struct TruthBox {
  uint64_t id = 0;
  OrientedBox box;
  cv::Vec2d velocity;  // ground motion seen in the current image, px/frame
  bool visible = false;
  bool moving = false;
};

struct SyntheticFrame {
  MotionEstimate motion;
  SegmentationResult segmentation;
  std::vector<TruthBox> truth;
};

using CameraPath = std::function<Homography(int)>;  // frame -> ground-to-image homography

CameraPath static_camera();
// Translation (px/frame), rotation (deg/frame) about the image centre and zoom factor per frame.
CameraPath moving_camera(cv::Vec2d translation, double rotation_deg, double zoom, cv::Point2d centre = {320, 240});

class SyntheticScene {
 public:
  SyntheticScene(std::vector<ObjectPath> objects, CameraPath camera, SceneOptions options = {});

  // Frames from 1, in order.
  SyntheticFrame next();

  // Optional hook that edits the regions of a frame (e.g. to split one object's region).
  std::function<void(int frame, std::vector<Region>& regions, const std::vector<TruthBox>& truth)> edit_regions;

 private:
  OrientedBox ground_box(const ObjectPath& o, int frame) const;

  std::vector<ObjectPath> objects_;
  CameraPath camera_;
  SceneOptions options_;
  std::mt19937 rng_;
  std::vector<std::vector<cv::Point2d>> feature_uv_;
  std::vector<cv::Point2d> static_points_;
  std::map<uint64_t, double> last_heading_;
  int frame_ = 0;
};

// Scoring against the truth: a visible moving truth object is matched to the confirmed or coasting
// track with the highest IoU (at least `min_iou`).
struct Score {
  int truth_instances = 0;
  int matched = 0;
  double mean_position_error = 0.0;
  double max_position_error = 0.0;
  double mean_width_error = 0.0;
  double mean_length_error = 0.0;
  std::map<uint64_t, std::vector<uint64_t>> track_ids_of_truth;  // distinct ids in order of appearance
  int unmatched_confirmed_tracks = 0;  // confirmed track-frames overlapping no truth object
  std::set<uint64_t> all_confirmed_ids;
};

struct RunOptions {
  int frames = 100;
  int score_from_frame = 10;  // let tracks confirm first
  double min_iou = 0.3;
  // Replace the homography given to the tracker (e.g. by the identity, to show the control input matters).
  std::function<void(MotionEstimate&)> edit_motion;
};

inline RunOptions run_for(int frames) {
  RunOptions run;
  run.frames = frames;
  return run;
}

Score run_and_score(SyntheticScene& scene, Tracker& tracker, const RunOptions& run);

// Straight ground path: start + velocity * (frame - 1).
std::function<cv::Point2d(int)> straight(cv::Point2d start, cv::Vec2d velocity);

// Ground path at `speed` px/frame along `heading_deg(frame)`: frame 1 at `start`, each later frame one
// step along that frame's heading.
std::function<cv::Point2d(int)> along_heading(cv::Point2d start, double speed, std::function<double(int)> heading_deg);

// A piece of `whole` as segmentation reports a fragment of an object: `length` px long, centred at
// `centre_u` along the whole box's length (box coordinates, -0.5 rear .. 0.5 front), same width and angle.
Region piece_of(const Region& whole, double centre_u, double length);

}  // namespace uavmot::tracking::testing
