#pragma once
// A SORT-like tracker (Bewley et al. 2016) for the classic baseline: one constant-velocity Kalman
// filter per track on (cx, cy, area, aspect), boxes matched to predictions by IoU (greedy, best
// pair first), new tracks from unmatched boxes, tracks reported after `min_hits` consecutive
// matches and dropped after `max_age` frames without one. One addition for a moving camera: each
// track's state is carried into the next frame with the frame-to-frame homography before the
// prediction.

#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/video/tracking.hpp>

namespace uavmot::classic {

struct SortOptions {
  int min_hits = 3;
  int max_age = 3;
  double min_iou = 0.1;  // small boxes of fast vehicles overlap little between frames
};

struct SortBox {
  int id = 0;
  cv::Rect2d box;
};

class SortTracker {
 public:
  explicit SortTracker(SortOptions options) : options_(options) {}
  // Boxes of frame k and the homography k -> k+1; returns the confirmed tracks matched in frame k.
  std::vector<SortBox> update(const std::vector<cv::Rect>& boxes, const cv::Matx33d& to_next);

 private:
  struct Track {
    cv::KalmanFilter kalman;
    int id = 0, hits = 0, streak = 0, since_update = 0;
  };
  static Track start(const cv::Rect& box, int id);
  static cv::Rect2d box_of(const cv::KalmanFilter& k);

  SortOptions options_;
  std::vector<Track> tracks_;
  int next_id_ = 1;
  int frames_ = 0;
};

}  // namespace uavmot::classic
