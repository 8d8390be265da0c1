#pragma once
// The classic detector uavmot is compared with: per frame pair, goodFeaturesToTrack +
// calcOpticalFlowPyrLK + findHomography (RANSAC) for the camera motion, then motion-compensated
// three-frame differencing: frame k-1 and frame k+1 are warped onto frame k, both absolute
// differences are thresholded, their union (or, with both_differences, their AND: only where the
// mover is in frame k) is cleaned by morphology, and its connected components are the detections
// of frame k, ready one frame later. The defaults are the best of a small grid on 40 frames of
// `uavmot sim --preset hd --seed 1` (docs/benchmarks/process.md): the AND loses most slow
// vehicles, whose two differences overlap only at their ends.

#include <optional>
#include <vector>

#include <opencv2/core.hpp>

namespace uavmot::classic {

struct DifferenceOptions {
  int max_corners = 1000;          // goodFeaturesToTrack, as OpenCV's videostab default
  double corner_quality = 0.01;
  double corner_distance_px = 8.0;
  int lk_window_px = 21;
  int lk_levels = 3;
  double ransac_px = 3.0;
  int threshold = 10;              // grey levels of |I_k - warped I_k±1|
  bool both_differences = false;   // AND of the two differences (else OR: where it was or will be too)
  int close_px = 5;                // closing joins a vehicle's parts (roof, windscreen, rim)
  int open_px = 3;                 // opening removes noise specks
  int min_area_px = 15;            // smaller components are noise
  int max_area_px = 4000;          // larger ones are misregistration
};

struct Detections {
  int frame = 0;                   // the frame the boxes belong to (1-based)
  cv::Matx33d homography_to_next;  // frame -> frame+1 (the tracker's camera compensation)
  std::vector<cv::Rect> boxes;
};

class FrameDifferenceDetector {
 public:
  explicit FrameDifferenceDetector(DifferenceOptions options) : options_(options) {}
  // Feeds frame `index` (grey); returns the detections of the frame before it once three frames are in.
  std::optional<Detections> push(int index, const cv::Mat& grey);

 private:
  cv::Matx33d homography(const cv::Mat& from, const cv::Mat& to) const;
  cv::Mat moving_mask(const cv::Mat& centre, const cv::Mat& before, const cv::Matx33d& before_to_centre, const cv::Mat& after,
                      const cv::Matx33d& centre_to_after) const;

  DifferenceOptions options_;
  cv::Mat before_, centre_;        // frames k-1 and k
  cv::Matx33d before_to_centre_ = cv::Matx33d::eye();
  int centre_index_ = 0;
};

}  // namespace uavmot::classic
