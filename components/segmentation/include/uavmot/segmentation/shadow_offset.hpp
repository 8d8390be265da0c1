#pragma once
// Where the vehicles' shadows lie, learnt from the regions themselves.
//
// In sunlight a vehicle's gradient blob is its body and its shadow: the sun is the same for every
// vehicle, so every box is pulled the same way (on the simulator's `paper` scenes about +1.1 / +0.8
// px in x / y on every seed, most of its position error; docs/segmentation.md, "Shadows").
//
// Model: a box is a body B united with its shadow B + s for one image offset s. For a candidate s
// the body is the box shrunk by |s| along each axis and moved back by s / 2, and the shadow alone is
// the band of the box at the far end of s (along the length and across): on a body brighter than
// the road that band is darker than the road, and the band of the same width just outside the
// box's other end is road. Each region whose body is clearly brighter than the road around it
// (a dark car gives no such contrast and would pull s long) scores every candidate s by the band's
// darkness less the outside band's. The best candidate, once enough regions have voted, is the
// offset the boxes are corrected by, when the regions agree: the votes are dealt alternately into two
// halves, whose own best candidates must lie within agreement_px (in an oblique view, where the
// GSD and so the shadow's length in pixels change across the image, they do not, and a single
// offset would move the boxes by noise). One frame's regions vote (reset() between frames), so a
// segmenter keeps no state that a restarted one could not rebuild (docs/launch.md, "Faults").

#include <optional>
#include <vector>

#include <opencv2/core/mat.hpp>
#include <opencv2/core/types.hpp>

#include "uavmot/core/oriented_box.hpp"

namespace uavmot::segmentation {

struct ShadowOffsetOptions {
  double max_offset_px = 10.0;     // candidates s with |s_x|, |s_y| up to this
  double step_px = 0.25;           // candidate grid spacing
  double bright_margin = 15.0;     // a body's upper quartile this far above the road (grey levels)
  int min_regions = 10;            // voting regions before an estimate is given
  double agreement_px = 1.0;       // the two halves of the votes must find offsets this close
  double min_darkness = 0.0;       // the shadow bands' mean darkness must exceed this (grey levels)
};

// A blob of a body united with its shadow moved by `shadow` reaches |shadow| further along each of
// its box's axes than the body: the blob's box shrunk by that much on the length and the width,
// never below half of either (an offset the box cannot hold). The centre is left as it is.
OrientedBox shrunk_by_shadow(const OrientedBox& blob, const cv::Vec2d& shadow);

class ShadowOffset {
 public:
  explicit ShadowOffset(ShadowOffsetOptions options);

  // One region's vote: `gray` (CV_8UC1) is an image window whose top-left pixel is at `origin` in
  // the frame; `box` is the region's box in frame coordinates (before any correction). Regions
  // without a bright body, or too close to the window's border to see the bands, do not vote.
  void observe(const cv::Mat& gray, cv::Point origin, const OrientedBox& box);
  // The shadow's image offset (px), or nothing before enough regions voted or when no candidate
  // scores above zero (no shadows).
  std::optional<cv::Vec2d> offset() const;
  // Forgets every vote (a new frame).
  void reset();

  int votes() const { return votes_; }

 private:
  ShadowOffsetOptions options_;
  int half_;                    // candidates per side: the grid is (2 half_ + 1)^2
  // The grid's cells within the search radius and their offsets, listed once: every region scores
  // the same candidates.
  struct Candidate {
    size_t cell;
    double sx, sy;
  };
  std::vector<Candidate> candidates_;
  std::vector<double> score_;   // row-major, s = ((col - half_) step, (row - half_) step)
  std::vector<double> odd_;     // the same for every second vote only
  std::vector<double> band_darkness_, band_pixels_;  // each candidate's shadow bands alone
  int votes_ = 0;
  // Scratch of observe(), kept so that the many regions of a frame do not allocate.
  struct Pixel {
    double u, v, grey;
  };
  std::vector<Pixel> pixels_;
  std::vector<double> road_, body_;
};

}  // namespace uavmot::segmentation
