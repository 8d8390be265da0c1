#pragma once
// Plane + parallax: tells static 3-D structure (roofs, walls, trees, parked trucks) from objects
// that move on their own, after the ground-plane homography has been compensated.
//
// A static point above the ground leaves a residual motion against the ground-plane homography
// when the camera translates. By the plane + parallax decomposition (Irani & Anandan 1996;
// Sawhney et al. 2000) that residual lies on the line through the point and the epipole e (the
// image of the camera's translation), on the same side for every point above the plane, and its
// size grows with the point's height. An independently moving object's residual is its own
// motion: in general off that line, or on the wrong side, or larger than any structure gives.
//
// Each frame, ParallaxFilter fits e by RANSAC over the features' relative velocities (two lines
// fix a hypothesis; the support counts features on their line, on the common side). The fit is
// trusted only when the support is many features spread over the image (structure is; one road
// of vehicles is a strip) and the epipole has been stable for a few frames (the camera's
// direction of travel changes slowly; a chance alignment of vehicles does not persist). Then a
// feature's velocity ALONG its epipolar line, on the structure side and up to the parallax the
// tallest structure could have there (the cap: a fraction of the ground's image motion, set by
// parallax_max_height_ratio), is explained as parallax and removed before the moving/static
// decision; what is left across the line is independent motion, and a velocity on the wrong side
// or beyond the cap is independent motion as a whole. Velocities beyond the cap take no part in
// the fit either: fast vehicles on a road along the flight would otherwise pull the epipole.

#include <cstdint>
#include <vector>

#include <opencv2/core/matx.hpp>
#include <opencv2/core/types.hpp>

#include "uavmot/motion/motion_options.hpp"

namespace uavmot::motion {

struct ParallaxSample {
  cv::Point2f position;        // current frame
  cv::Vec2d velocity{0, 0};    // relative to the compensated ground, px/frame
  double sigma = 0.0;          // 1-sigma of each velocity component
  double ground_flow_px = 0.0; // the ground's image motion at `position` this frame (px/frame)
};

struct ParallaxModel {
  bool valid = false;          // trusted: used to explain velocities
  bool provisional = false;    // a stream's first frames: trusted without the support density and the
                               // stability count, also used to explain velocities (not carried on)
  cv::Vec3d epipole{0, 0, 0};  // homogeneous, image coordinates of the current frame
  int side = 1;                // structure's residual points along side * epipolar_direction(); 0 = either way
  int candidates = 0;          // features with a residual clearly above their noise
  int support = 0;             // of those, consistent with the epipole
  double spread_px = 0.0;      // sqrt of the smaller eigenvalue of the supporters' position covariance
  double cap_px = 0.0;         // parallax_cap_factor x the supporters' median parallax (0: off); parallax_cap() caps too
  int stable_frames = 0;       // consecutive frames with a consistent epipole
};

class ParallaxFilter {
 public:
  explicit ParallaxFilter(const MotionOptions& options) : options_(options) {}

  // Fits this frame's epipole to the samples (deterministic: the hypotheses are drawn from a
  // generator seeded by `frame_index`). `stream_frame`: 1 for the estimator's first frame since it
  // started or was reset. Returns the model, valid only when trusted.
  const ParallaxModel& fit(const std::vector<ParallaxSample>& samples, cv::Size image_size, int64_t frame_index,
                           int64_t stream_frame);

  // The part of `sample.velocity` that parallax does not explain under `model` (the velocity
  // itself when the model is neither valid nor provisional).
  cv::Vec2d independent_velocity(const ParallaxSample& sample) const;

  // How static structure can move at `sample` under the model: along `direction` (and against it
  // too when `both_ways`) by up to `cap_px` per frame, the bound independent_velocity() explains.
  // False when the model is neither valid nor provisional.
  struct StructureMotion {
    cv::Vec2d direction{0, 0};
    double cap_px = 0.0;
    bool both_ways = false;
  };
  bool structure_motion(const ParallaxSample& sample, StructureMotion& out) const;

  const ParallaxModel& model() const { return model_; }
  // Where the last fit found structure: the positions of its supporters (empty unless valid or provisional).
  const std::vector<cv::Point2f>& supporters() const { return supporters_; }
  void reset() {
    model_ = ParallaxModel{};
    supporters_.clear();
  }
  // The model is all a fit carries to the next frame's (a saved estimator state).
  void restore(const ParallaxModel& model) { model_ = model; }

 private:
  const MotionOptions& options_;
  ParallaxModel model_;
  std::vector<cv::Point2f> supporters_;
};

// The largest parallax a static point at `sample` can have: structure up to a height h under a
// camera at H moves against the ground by h / (H - h) of the ground's own image motion there.
double parallax_cap(const ParallaxSample& sample, const MotionOptions& options);

// Unit direction at `point` along the epipolar line, pointing away from the epipole (for an
// epipole at infinity: the direction towards it, reversed). Zero at the epipole itself.
cv::Vec2d epipolar_direction(const cv::Vec3d& epipole, const cv::Point2f& point);

}  // namespace uavmot::motion
