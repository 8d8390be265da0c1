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
  // Background reachable from the border (4-connected) is outside; the rest is filled. A
  // continuous copy, indices into it and a stack of them: no per-pixel bounds logic of Mat::at.
  cv::Mat state = mask.clone();  // continuous; 0 is background
  uchar* s = state.data;
  constexpr uchar kOutside = 1, kSet = 255;
  for (int i = 0; i < rows * cols; ++i) s[i] = s[i] != 0 ? kSet : 0;
  std::vector<int> stack;
  auto visit = [&](int i) {
    if (s[i] != 0) return;
    s[i] = kOutside;
    stack.push_back(i);
  };
  for (int x = 0; x < cols; ++x) visit(x), visit((rows - 1) * cols + x);
  for (int y = 0; y < rows; ++y) visit(y * cols), visit(y * cols + cols - 1);
  while (!stack.empty()) {
    const int i = stack.back();
    stack.pop_back();
    const int x = i % cols;
    if (x + 1 < cols) visit(i + 1);
    if (x > 0) visit(i - 1);
    if (i + cols < rows * cols) visit(i + cols);
    if (i >= cols) visit(i - cols);
  }
  for (int y = 0; y < rows; ++y) {
    uchar* m = mask.ptr<uchar>(y);
    const uchar* o = s + static_cast<size_t>(y) * cols;
    for (int x = 0; x < cols; ++x) m[x] = o[x] == kOutside ? 0 : 255;
  }
}

}  // namespace uavmot::segmentation
