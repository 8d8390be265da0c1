#include "min_eigen_map.hpp"

#include <cmath>
#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

namespace uavmot::motion {
namespace {

// Integer 3x3 Sobel products along one row: xx = dx^2, xy = dx dy, yy = dy^2 at x = 0..width-1 of
// `mid` (which, with `up` and `down`, must be readable at -1 and width). Restrict-qualified
// parameters let the compiler vectorise (the grey bytes could otherwise alias the output).
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

// The same where columns are reflected at the image border: column j of the row is image column
// at[j], its neighbours left[j] and right[j].
void sobel_products_gathered(const uchar* up, const uchar* mid, const uchar* down, const std::vector<int>& left,
                             const std::vector<int>& at, const std::vector<int>& right, int32_t* xx, int32_t* xy,
                             int32_t* yy) {
  for (size_t j = 0; j < at.size(); ++j) {
    const int l = left[j], c = at[j], r = right[j];
    const int dx = (up[r] - up[l]) + 2 * (mid[r] - mid[l]) + (down[r] - down[l]);
    const int dy = (down[l] + 2 * down[c] + down[r]) - (up[l] + 2 * up[c] + up[r]);
    xx[j] = dx * dx;
    xy[j] = dx * dy;
    yy[j] = dy * dy;
  }
}

// sum += in and sum -= in, elementwise (exact in integers: block sums of 8-bit Sobel products stay
// below 15 x 15 x 1020^2 < 2^31).
void add(int32_t* __restrict sum, const int32_t* __restrict in, size_t n) {
  for (size_t i = 0; i < n; ++i) sum[i] += in[i];
}
void subtract(int32_t* __restrict sum, const int32_t* __restrict in, size_t n) {
  for (size_t i = 0; i < n; ++i) sum[i] -= in[i];
}

// One output row from the column sums of the block's rows: the block sums along the row (sliding,
// exact), then the smaller eigenvalue.
void eigen_row(const int32_t* sum_xx, const int32_t* sum_xy, const int32_t* sum_yy, int width, int block,
               double scale2, double floor, float* out) {
  int32_t a = 0, b = 0, c = 0;
  for (int k = 0; k < block; ++k) {
    a += sum_xx[k];
    b += sum_xy[k];
    c += sum_yy[k];
  }
  for (int x = 0; x < width; ++x) {
    if (x > 0) {
      a += sum_xx[x + block - 1] - sum_xx[x - 1];
      b += sum_xy[x + block - 1] - sum_xy[x - 1];
      c += sum_yy[x + block - 1] - sum_yy[x - 1];
    }
    // cornerMinEigenVal's formula: (a + c) / 2 - sqrt(((a - c) / 2)^2 + b^2). The first term bounds
    // the value from above (rounding is monotonic), so below the floor no root is needed.
    const double half_trace = 0.5 * (static_cast<double>(a) + static_cast<double>(c));
    if (half_trace * scale2 < floor) {
      out[x] = 0.0f;
      continue;
    }
    const double half_difference = 0.5 * (static_cast<double>(a) - static_cast<double>(c));
    const double bd = static_cast<double>(b);
    const double value = (half_trace - std::sqrt(half_difference * half_difference + bd * bd)) * scale2;
    out[x] = value < floor ? 0.0f : static_cast<float>(value);
  }
}

}  // namespace

void min_eigen_values(const cv::Mat& gray, const cv::Rect& region, int block, double floor, cv::Mat& out) {
  CV_Assert(gray.type() == CV_8UC1 && block >= 1 && block % 2 == 1);
  out.create(region.size(), CV_32F);
  if (region.empty()) return;
  CV_Assert((region & cv::Rect(0, 0, gray.cols, gray.rows)) == region);
  const int half = block / 2;
  // cornerMinEigenVal scales the 3x3 Sobel of an 8-bit image by 1 / (4 block 255).
  const double scale = 1.0 / (4.0 * block * 255.0);
  const double scale2 = scale * scale;
  // Products are needed over the region grown by the box's half; where that (or the Sobel's own
  // neighbour) leaves the image, cornerMinEigenVal reflects (BORDER_REFLECT_101): the image for
  // the Sobel, the products for the box.
  const int w = region.width + 2 * half;
  const int x0 = region.x - half;
  const bool inside = x0 - 1 >= 0 && x0 + w + 1 <= gray.cols;
  std::vector<int> left, at, right;
  if (!inside) {
    left.resize(static_cast<size_t>(w));
    at.resize(static_cast<size_t>(w));
    right.resize(static_cast<size_t>(w));
    for (int j = 0; j < w; ++j) {
      const int c = cv::borderInterpolate(x0 + j, gray.cols, cv::BORDER_REFLECT_101);
      at[static_cast<size_t>(j)] = c;
      left[static_cast<size_t>(j)] = cv::borderInterpolate(c - 1, gray.cols, cv::BORDER_REFLECT_101);
      right[static_cast<size_t>(j)] = cv::borderInterpolate(c + 1, gray.cols, cv::BORDER_REFLECT_101);
    }
  }
  // The block's rows of products in a ring, and their column sums.
  const size_t row_size = 3 * static_cast<size_t>(w);
  std::vector<int32_t> ring(static_cast<size_t>(block) * row_size);
  std::vector<int32_t> sums(row_size, 0);
  auto products_of = [&](int product_row, int32_t* dst) {  // product_row: 0 = region.y - half
    const int r = cv::borderInterpolate(region.y - half + product_row, gray.rows, cv::BORDER_REFLECT_101);
    const uchar* up = gray.ptr<uchar>(cv::borderInterpolate(r - 1, gray.rows, cv::BORDER_REFLECT_101));
    const uchar* mid = gray.ptr<uchar>(r);
    const uchar* down = gray.ptr<uchar>(cv::borderInterpolate(r + 1, gray.rows, cv::BORDER_REFLECT_101));
    if (inside) {
      sobel_products(up + x0, mid + x0, down + x0, w, dst, dst + w, dst + 2 * w);
    } else {
      sobel_products_gathered(up, mid, down, left, at, right, dst, dst + w, dst + 2 * w);
    }
  };
  for (int k = 0; k < block; ++k) {
    int32_t* row = ring.data() + static_cast<size_t>(k) * row_size;
    products_of(k, row);
    add(sums.data(), row, row_size);
  }
  for (int y = 0; y < region.height; ++y) {
    if (y > 0) {
      // The block moves down one row: the oldest row leaves the ring, the next one enters.
      int32_t* slot = ring.data() + static_cast<size_t>((y - 1) % block) * row_size;
      subtract(sums.data(), slot, row_size);
      products_of(y + block - 1, slot);
      add(sums.data(), slot, row_size);
    }
    eigen_row(sums.data(), sums.data() + w, sums.data() + 2 * w, region.width, block, scale2, floor, out.ptr<float>(y));
  }
}

}  // namespace uavmot::motion
