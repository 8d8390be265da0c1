#include "frame_difference.hpp"

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>

namespace uavmot::classic {

cv::Matx33d FrameDifferenceDetector::homography(const cv::Mat& from, const cv::Mat& to) const {
  std::vector<cv::Point2f> corners, moved;
  cv::goodFeaturesToTrack(from, corners, options_.max_corners, options_.corner_quality, options_.corner_distance_px);
  if (corners.size() < 8) return cv::Matx33d::eye();
  std::vector<unsigned char> status;
  std::vector<float> error;
  cv::calcOpticalFlowPyrLK(from, to, corners, moved, status, error, cv::Size(options_.lk_window_px, options_.lk_window_px),
                           options_.lk_levels);
  std::vector<cv::Point2f> src, dst;
  for (size_t i = 0; i < corners.size(); ++i) {
    if (status[i]) {
      src.push_back(corners[i]);
      dst.push_back(moved[i]);
    }
  }
  if (src.size() < 8) return cv::Matx33d::eye();
  const cv::Mat h = cv::findHomography(src, dst, cv::RANSAC, options_.ransac_px);
  return h.empty() ? cv::Matx33d::eye() : cv::Matx33d(h);
}

cv::Mat FrameDifferenceDetector::moving_mask(const cv::Mat& centre, const cv::Mat& before, const cv::Matx33d& before_to_centre,
                                             const cv::Mat& after, const cv::Matx33d& centre_to_after) const {
  auto changed = [&](const cv::Mat& other, const cv::Matx33d& other_to_centre) {
    cv::Mat warped, diff, mask;
    // Replicated borders: where the warp has no source (a pixel-wide strip at this camera speed) the
    // difference stays small, at no cost for a validity mask.
    cv::warpPerspective(other, warped, other_to_centre, centre.size(), cv::INTER_LINEAR, cv::BORDER_REPLICATE);
    cv::absdiff(centre, warped, diff);
    cv::threshold(diff, mask, options_.threshold, 255, cv::THRESH_BINARY);
    return mask;
  };
  const cv::Mat to_before = changed(before, before_to_centre), to_after = changed(after, centre_to_after.inv());
  cv::Mat mask = options_.both_differences ? (to_before & to_after) : (to_before | to_after);
  const auto square = [](int px) { return cv::getStructuringElement(cv::MORPH_RECT, cv::Size(px, px)); };
  cv::morphologyEx(mask, mask, cv::MORPH_CLOSE, square(options_.close_px));
  cv::morphologyEx(mask, mask, cv::MORPH_OPEN, square(options_.open_px));
  return mask;
}

std::optional<Detections> FrameDifferenceDetector::push(int index, const cv::Mat& grey) {
  std::optional<Detections> out;
  if (!centre_.empty()) {
    const cv::Matx33d centre_to_after = homography(centre_, grey);
    if (!before_.empty()) {
      const cv::Mat mask = moving_mask(centre_, before_, before_to_centre_, grey, centre_to_after);
      cv::Mat labels, stats, centroids;
      const int n = cv::connectedComponentsWithStats(mask, labels, stats, centroids, 8, CV_32S);
      Detections d;
      d.frame = centre_index_;
      d.homography_to_next = centre_to_after;
      for (int i = 1; i < n; ++i) {
        const int area = stats.at<int>(i, cv::CC_STAT_AREA);
        if (area < options_.min_area_px || area > options_.max_area_px) continue;
        d.boxes.emplace_back(stats.at<int>(i, cv::CC_STAT_LEFT), stats.at<int>(i, cv::CC_STAT_TOP),
                             stats.at<int>(i, cv::CC_STAT_WIDTH), stats.at<int>(i, cv::CC_STAT_HEIGHT));
      }
      out = std::move(d);
    }
    before_to_centre_ = centre_to_after;
  }
  before_ = centre_;
  centre_ = grey;
  centre_index_ = index;
  return out;
}

}  // namespace uavmot::classic
