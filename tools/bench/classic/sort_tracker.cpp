#include "sort_tracker.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>

namespace uavmot::classic {
namespace {

cv::Mat measurement_of(const cv::Rect2d& b) {
  return (cv::Mat_<float>(4, 1) << static_cast<float>(b.x + b.width / 2), static_cast<float>(b.y + b.height / 2),
          static_cast<float>(b.area()), static_cast<float>(b.width / std::max(b.height, 1e-6)));
}

double iou(const cv::Rect2d& a, const cv::Rect2d& b) {
  const double inter = (a & b).area();
  const double uni = a.area() + b.area() - inter;
  return uni > 0 ? inter / uni : 0.0;
}

}  // namespace

// State (cx, cy, s, r, vcx, vcy, vs), measurement (cx, cy, s, r): SORT's model and noise levels.
SortTracker::Track SortTracker::start(const cv::Rect& box, int id) {
  Track t;
  t.id = id;
  cv::KalmanFilter& k = t.kalman;
  k.init(7, 4, 0, CV_32F);
  cv::setIdentity(k.transitionMatrix);
  for (int i = 0; i < 3; ++i) k.transitionMatrix.at<float>(i, i + 4) = 1.0f;
  k.measurementMatrix = cv::Mat::zeros(4, 7, CV_32F);
  for (int i = 0; i < 4; ++i) k.measurementMatrix.at<float>(i, i) = 1.0f;
  cv::setIdentity(k.measurementNoiseCov, cv::Scalar(1.0f));
  k.measurementNoiseCov.at<float>(2, 2) = k.measurementNoiseCov.at<float>(3, 3) = 10.0f;
  cv::setIdentity(k.errorCovPost, cv::Scalar(10.0f));
  for (int i = 4; i < 7; ++i) k.errorCovPost.at<float>(i, i) = 1000.0f;
  cv::setIdentity(k.processNoiseCov, cv::Scalar(1.0f));
  k.processNoiseCov.at<float>(6, 6) = 0.01f;
  for (int i = 4; i < 6; ++i) k.processNoiseCov.at<float>(i, i) = 0.01f;
  k.statePost = cv::Mat::zeros(7, 1, CV_32F);
  measurement_of(box).copyTo(k.statePost.rowRange(0, 4));
  return t;
}

cv::Rect2d SortTracker::box_of(const cv::KalmanFilter& k) {
  const cv::Mat& x = k.statePost;
  const double s = std::max(x.at<float>(2), 1.0f), r = std::max(x.at<float>(3), 1e-3f);
  const double w = std::sqrt(s * r), h = s / w;
  return {x.at<float>(0) - w / 2, x.at<float>(1) - h / 2, w, h};
}

std::vector<SortBox> SortTracker::update(const std::vector<cv::Rect>& boxes, const cv::Matx33d& to_next) {
  ++frames_;
  std::vector<cv::Rect2d> predicted;
  for (Track& t : tracks_) {
    const cv::Mat p = t.kalman.predict();
    p.copyTo(t.kalman.statePost);  // the prediction stands until a match corrects it
    predicted.push_back(box_of(t.kalman));
    ++t.since_update;
  }
  // Greedy IoU matching, best pair first (SORT solves the same matrix with the Hungarian method).
  std::vector<std::tuple<double, size_t, size_t>> pairs;
  for (size_t i = 0; i < tracks_.size(); ++i) {
    for (size_t j = 0; j < boxes.size(); ++j) {
      const double o = iou(predicted[i], cv::Rect2d(boxes[j]));
      if (o >= options_.min_iou) pairs.emplace_back(o, i, j);
    }
  }
  std::sort(pairs.begin(), pairs.end(), [](const auto& a, const auto& b) { return std::get<0>(a) > std::get<0>(b); });
  std::vector<bool> track_used(tracks_.size(), false), box_used(boxes.size(), false);
  for (const auto& [o, i, j] : pairs) {
    if (track_used[i] || box_used[j]) continue;
    track_used[i] = box_used[j] = true;
    Track& t = tracks_[i];
    t.kalman.correct(measurement_of(cv::Rect2d(boxes[j])));
    t.since_update = 0;
    ++t.hits;
    ++t.streak;
  }
  for (size_t i = 0; i < tracks_.size(); ++i) {
    if (!track_used[i]) tracks_[i].streak = 0;
  }
  for (size_t j = 0; j < boxes.size(); ++j) {
    if (!box_used[j]) tracks_.push_back(start(boxes[j], next_id_++));
  }
  std::vector<SortBox> out;
  for (const Track& t : tracks_) {
    if (t.since_update == 0 && (t.streak >= options_.min_hits || frames_ <= options_.min_hits)) out.push_back({t.id, box_of(t.kalman)});
  }
  tracks_.erase(std::remove_if(tracks_.begin(), tracks_.end(), [&](const Track& t) { return t.since_update > options_.max_age; }),
                tracks_.end());
  // Carry every track into the next frame's coordinates: the camera moved by `to_next`.
  for (Track& t : tracks_) {
    cv::Mat& x = t.kalman.statePost;
    const cv::Vec3d c = to_next * cv::Vec3d(x.at<float>(0), x.at<float>(1), 1.0);
    const cv::Vec3d v = to_next * cv::Vec3d(x.at<float>(0) + x.at<float>(4), x.at<float>(1) + x.at<float>(5), 1.0);
    x.at<float>(0) = static_cast<float>(c[0] / c[2]);
    x.at<float>(1) = static_cast<float>(c[1] / c[2]);
    x.at<float>(4) = static_cast<float>(v[0] / v[2] - c[0] / c[2]);
    x.at<float>(5) = static_cast<float>(v[1] / v[2] - c[1] / c[2]);
  }
  return out;
}

}  // namespace uavmot::classic
