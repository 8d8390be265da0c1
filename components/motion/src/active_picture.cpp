#include "active_picture.hpp"

#include <algorithm>

namespace uavmot::motion {
namespace {

// True when `line` (one row or one column, CV_8UC1) is black band.
bool blank_line(const cv::Mat& line, double max_mean, double max_grey) {
  int sum = 0, brightest = 0;
  for (int y = 0; y < line.rows; ++y) {
    const uchar* p = line.ptr<uchar>(y);
    for (int x = 0; x < line.cols; ++x) {
      sum += p[x];
      brightest = std::max(brightest, static_cast<int>(p[x]));
    }
  }
  return brightest <= max_grey && sum <= max_mean * static_cast<double>(line.total());
}

}  // namespace

cv::Rect active_picture_area(const cv::Mat& gray, const MotionOptions& o) {
  const cv::Rect whole(0, 0, gray.cols, gray.rows);
  const double max_mean = o.blank_band_max_grey;
  if (max_mean <= 0.0 || gray.empty()) return whole;
  const double max_grey = 4.0 * max_mean;
  const int max_cols = gray.cols / 8, max_rows = gray.rows / 8;
  int left = 0, right = 0, top = 0, bottom = 0;
  while (left < max_cols && blank_line(gray.col(left), max_mean, max_grey)) ++left;
  while (right < max_cols && blank_line(gray.col(gray.cols - 1 - right), max_mean, max_grey)) ++right;
  while (top < max_rows && blank_line(gray.row(top), max_mean, max_grey)) ++top;
  while (bottom < max_rows && blank_line(gray.row(gray.rows - 1 - bottom), max_mean, max_grey)) ++bottom;
  // A band's inner edge is soft: the aphill clips' first picture column after the black is 28-64
  // grey levels (blanking's ramp) or a ringing overshoot. Those lines are fixed in the image too.
  constexpr int kSoftEdgePx = 2;
  for (int* band : {&left, &right, &top, &bottom}) {
    if (*band > 0) *band += kSoftEdgePx;
  }
  return cv::Rect(left, top, std::max(0, gray.cols - left - right), std::max(0, gray.rows - top - bottom));
}

cv::Rect usable_area(const cv::Rect& picture, int border_px) {
  const int width = picture.width - 2 * border_px, height = picture.height - 2 * border_px;
  if (width <= 0 || height <= 0) return cv::Rect(picture.x + border_px, picture.y + border_px, 0, 0);
  return cv::Rect(picture.x + border_px, picture.y + border_px, width, height);
}

}  // namespace uavmot::motion
