#include "binary_mask.hpp"

#include <algorithm>
#include <vector>

namespace uavmot::segmentation {
namespace {

// One separable pass along rows (`along_rows`) or columns of a rectangle filter: dilation sets a
// pixel when any pixel of its clipped window is set, erosion when all of them are.
void pass(const cv::Mat& src, cv::Mat& dst, int half, bool along_rows, bool dilate) {
  const int lines = along_rows ? src.rows : src.cols, length = along_rows ? src.cols : src.rows;
  // Byte distance between neighbouring lines and between neighbouring pixels of one line.
  const size_t src_line = along_rows ? src.step[0] : 1, src_pixel = along_rows ? 1 : src.step[0];
  const size_t dst_line = along_rows ? dst.step[0] : 1, dst_pixel = along_rows ? 1 : dst.step[0];
  std::vector<int> prefix(static_cast<size_t>(length) + 1, 0);
  for (int line = 0; line < lines; ++line) {
    const uchar* in = src.data + line * src_line;
    uchar* out = dst.data + line * dst_line;
    for (int i = 0; i < length; ++i) prefix[i + 1] = prefix[i] + (in[i * src_pixel] != 0 ? 1 : 0);
    for (int i = 0; i < length; ++i) {
      const int lo = std::max(0, i - half), hi = std::min(length - 1, i + half);
      const int set = prefix[hi + 1] - prefix[lo];
      out[i * dst_pixel] = (dilate ? set > 0 : set == hi - lo + 1) ? 255 : 0;
    }
  }
}

}  // namespace

void close_binary(cv::Mat& mask, int size) {
  CV_Assert(mask.type() == CV_8UC1 && size % 2 == 1);
  if (size <= 1 || mask.empty()) return;
  const int half = size / 2;
  cv::Mat buffer(mask.size(), CV_8U);
  // A rectangle's max (min) is the max (min) over columns of the max (min) over rows.
  pass(mask, buffer, half, true, true);
  pass(buffer, mask, half, false, true);
  pass(mask, buffer, half, true, false);
  pass(buffer, mask, half, false, false);
}

void fill_holes(cv::Mat& mask) {
  CV_Assert(mask.type() == CV_8UC1);
  const int rows = mask.rows, cols = mask.cols;
  if (rows == 0 || cols == 0) return;
  // Background reachable from the border (4-connected) is outside; the rest is filled.
  cv::Mat outside = cv::Mat::zeros(mask.size(), CV_8U);
  std::vector<cv::Point> stack;
  auto visit = [&](int x, int y) {
    if (x < 0 || y < 0 || x >= cols || y >= rows) return;
    if (mask.at<uchar>(y, x) != 0 || outside.at<uchar>(y, x) != 0) return;
    outside.at<uchar>(y, x) = 1;
    stack.emplace_back(x, y);
  };
  for (int x = 0; x < cols; ++x) visit(x, 0), visit(x, rows - 1);
  for (int y = 0; y < rows; ++y) visit(0, y), visit(cols - 1, y);
  while (!stack.empty()) {
    const cv::Point p = stack.back();
    stack.pop_back();
    visit(p.x + 1, p.y);
    visit(p.x - 1, p.y);
    visit(p.x, p.y + 1);
    visit(p.x, p.y - 1);
  }
  for (int y = 0; y < rows; ++y) {
    uchar* m = mask.ptr<uchar>(y);
    const uchar* o = outside.ptr<uchar>(y);
    for (int x = 0; x < cols; ++x) m[x] = o[x] ? 0 : 255;
  }
}

}  // namespace uavmot::segmentation
