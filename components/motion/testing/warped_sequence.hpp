#pragma once
// Test and benchmark frames with exact ground truth, until the simulator is available: real
// CLIF 2007 texture (a mosaic of 9 frames) seen by a virtual camera moving along a smooth path,
// optionally with small textured patches that move over the ground (vehicles) or stand still
// (parked vehicles), plus seeded sensor noise.

#include <cstdint>
#include <string>
#include <vector>

#include <opencv2/core/mat.hpp>
#include <opencv2/core/types.hpp>

#include "uavmot/core/homography.hpp"

namespace uavmot::motion::testing {

struct Patch {
  cv::Point2d start;        // top-left corner in ground (mosaic) coordinates at frame 1
  cv::Vec2d velocity{0, 0};  // ground px/frame; zero for a parked vehicle
  cv::Size size{20, 10};
};

struct WarpedSequenceOptions {
  std::string clif_folder;             // .../clif2007/jpg
  cv::Size frame_size{960, 540};
  double camera_speed_px = 3.0;        // ground px/frame along camera_heading_deg
  double camera_heading_deg = 30.0;
  double rotation_deg_per_frame = 0.05;
  double zoom_per_frame = 0.0005;      // relative scale change per frame
  double jitter_px = 0.5;              // amplitude of smooth sinusoidal wobble
  double perspective = 2e-6;           // amplitude of the slowly varying projective terms
  double noise_sigma = 1.0;            // grey levels, Gaussian, seeded per frame
  uint64_t seed = 7;
  std::vector<Patch> patches;
};

class WarpedSequence {
 public:
  explicit WarpedSequence(WarpedSequenceOptions options);  // throws uavmot::InputError if the texture is missing

  // Frame k (from 1), CV_8UC1.
  cv::Mat frame(int k) const;
  // Ground -> frame k.
  Homography ground_to_frame(int k) const;
  // Exact homography frame k-1 -> frame k (identity for k = 1).
  Homography true_homography(int k) const;

  // Index of the patch that covers frame point p in frame k, shrunk by `inner_margin` px; -1 if
  // none; -2 if p lies in the band from `inner_margin` inside to `outer_margin` outside a patch
  // border (ambiguous: a tracking window there sees both the patch and the ground).
  int patch_at(int k, const cv::Point2d& p, double inner_margin, double outer_margin) const;
  // Velocity of patch i relative to the ground, in px/frame of frame k at point p.
  cv::Vec2d relative_velocity(int patch, int k, const cv::Point2d& p) const;

  // Replaces the patches (textures are seeded by index).
  void set_patches(std::vector<Patch> patches);

  const WarpedSequenceOptions& options() const { return options_; }
  cv::Size ground_size() const { return ground_.size(); }

 private:
  cv::Point2d patch_corner(int patch, int k) const;

  WarpedSequenceOptions options_;
  cv::Mat ground_;
  std::vector<cv::Mat> patch_textures_;
};

// Patches on a jittered grid over what the camera sees at frame `middle`, so they stay in view
// for most of the sequence: `moving` of them with speeds spread evenly over [min_speed,
// max_speed] in random directions, then `parked` standing still.
std::vector<Patch> scatter_patches(const WarpedSequence& sequence, int middle, int moving, int parked,
                                   double min_speed, double max_speed, uint64_t seed);

}  // namespace uavmot::motion::testing
