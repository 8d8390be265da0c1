#include "corner_bound.hpp"

#include <cstdint>
#include <vector>

namespace uavmot::motion {
namespace {

// Integer 3x3 Sobel products of one row: xx = dx^2, xy = dx dy, yy = dy^2 at x = 0..width-1 of `mid`
// (which, with `up` and `down`, must be readable at -1 and width). Restrict-qualified parameters
// let the compiler vectorise (the grey bytes could otherwise alias the output).
void sobel_products(const uchar* __restrict up, const uchar* __restrict mid, const uchar* __restrict down, int width,
                    int32_t* __restrict xx, int32_t* __restrict xy, int32_t* __restrict yy) {
  for (int x = 0; x < width; ++x) {
    const int dx = (up[x + 1] - up[x - 1]) + 2 * (mid[x + 1] - mid[x - 1]) + (down[x + 1] - down[x - 1]);
    const int dy = (down[x - 1] + 2 * down[x] + down[x + 1]) - (up[x - 1] + 2 * up[x] + up[x + 1]);
    xx[x] = dx * dx;
    xy[x] = dx * dy;
    yy[x] = dy * dy;
  }
}

// sum += in, elementwise.
void add(int32_t* __restrict sum, const int32_t* __restrict in, int width) {
  for (int x = 0; x < width; ++x) sum[x] += in[x];
}

// sum += in - out, elementwise (a block sum sliding one row down; exact in integers).
void slide(int32_t* __restrict sum, const int32_t* __restrict in, const int32_t* __restrict out, int width) {
  for (int x = 0; x < width; ++x) sum[x] += in[x] - out[x];
}

}  // namespace

// Computes the gradient covariance [A B; B C] of every pixel exactly, in integers (3x3 Sobel, block
// sums), and passes the cell over only when its smaller eigenvalue stays below half the threshold
// less 1e-5 everywhere: cornerMinEigenVal computes the same eigenvalue in float (scaled, values of
// at most about 1), far closer than that margin, so no corner it would give is lost.
bool may_hold_corner(const cv::Mat& gray, const cv::Rect& cell, const MotionOptions& o) {
  const int block = o.corner_block_size;  // odd (validated): the box is centred
  const int half = block / 2;
  const int reach = half + 1;  // the box, then the Sobel aperture's own neighbour
  if (cell.x < reach || cell.y < reach || cell.x + cell.width + reach > gray.cols ||
      cell.y + cell.height + reach > gray.rows) {
    return true;  // the filters would read the border: no bound here
  }
  // cornerMinEigenVal scales the 3x3 Sobel of an 8-bit image by 1 / (4 * block * 255).
  const double scale = 1.0 / (4.0 * block * 255.0);
  const double limit = (0.5 * o.min_corner_response - 1e-5) / (scale * scale);  // in integer Sobel units squared
  if (!(limit > 0.0)) return true;
  // Products of the integer Sobel derivatives over the cell grown by the box's half. Block sums of
  // them reach at most 15 x 15 x 1020^2 < 2^31 (exact in 32 bits); the determinant needs 64.
  const int w = cell.width + 2 * half, h = cell.height + 2 * half;
  const size_t n = static_cast<size_t>(w) * static_cast<size_t>(h);
  std::vector<int32_t> products(3 * n + 3 * static_cast<size_t>(w));
  int32_t* dxx = products.data();
  int32_t* dxy = dxx + n;
  int32_t* dyy = dxy + n;
  for (int y = 0; y < h; ++y) {
    const int gy = cell.y - half + y, gx = cell.x - half;
    const size_t row = static_cast<size_t>(y) * w;
    sobel_products(gray.ptr<uchar>(gy - 1) + gx, gray.ptr<uchar>(gy) + gx, gray.ptr<uchar>(gy + 1) + gx, w, dxx + row,
                   dxy + row, dyy + row);
  }
  // Block sums, sliding (exact in integers): down the columns, then along each row of the cell.
  int32_t* sum_xx = dyy + n;
  int32_t* sum_xy = sum_xx + w;
  int32_t* sum_yy = sum_xy + w;
  for (int k = 0; k < block; ++k) {
    const size_t row = static_cast<size_t>(k) * w;
    add(sum_xx, dxx + row, w);
    add(sum_xy, dxy + row, w);
    add(sum_yy, dyy + row, w);
  }
  for (int y = 0; y < cell.height; ++y) {
    if (y > 0) {
      const size_t in = static_cast<size_t>(y + block - 1) * w, out = static_cast<size_t>(y - 1) * w;
      slide(sum_xx, dxx + in, dxx + out, w);
      slide(sum_xy, dxy + in, dxy + out, w);
      slide(sum_yy, dyy + in, dyy + out, w);
    }
    int32_t a = 0, b = 0, c = 0;
    for (int k = 0; k < block; ++k) {
      a += sum_xx[k];
      b += sum_xy[k];
      c += sum_yy[k];
    }
    for (int x = 0; x < cell.width; ++x) {
      if (x > 0) {
        a += sum_xx[x + block - 1] - sum_xx[x - 1];
        b += sum_xy[x + block - 1] - sum_xy[x - 1];
        c += sum_yy[x + block - 1] - sum_yy[x - 1];
      }
      // Smaller eigenvalue >= limit  <=>  (a + c) / 2 >= limit and a c - b^2 >= limit (a + c - limit).
      const double trace = static_cast<double>(a) + static_cast<double>(c);
      if (0.5 * trace < limit) continue;
      const int64_t det = static_cast<int64_t>(a) * c - static_cast<int64_t>(b) * b;
      if (static_cast<double>(det) >= limit * (trace - limit)) return true;
    }
  }
  return false;
}

}  // namespace uavmot::motion
