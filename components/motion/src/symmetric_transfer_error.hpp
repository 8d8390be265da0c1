#pragma once
// The residual block of the homography refinement: one correspondence's symmetric transfer error,
// with its derivatives written out.

#include <ceres/sized_cost_function.h>

namespace uavmot::motion {

// Residuals in pixels: H p - q (in frame k) and H^-1 q - p (in frame k-1). `h` holds the first
// eight entries of the normalised homography (h33 = 1); the inverse is the adjugate. Derivatives
// are written out: automatic differentiation (8-dimensional jets through two divisions and the
// adjugate) made the whole refinement 20 % dearer at 1080p. Checked against Ceres's jets in
// homography_refinement_test.cpp.
class SymmetricTransferError final : public ceres::SizedCostFunction<4, 8> {
 public:
  SymmetricTransferError(double px, double py, double qx, double qy, double to_px_forward, double to_px_backward)
      : px_(px), py_(py), qx_(qx), qy_(qy), to_px_forward_(to_px_forward), to_px_backward_(to_px_backward) {}

  bool Evaluate(double const* const* parameters, double* r, double** jacobians) const override {
    const double* h = parameters[0];
    // Forward: (u / w, v / w) against q.
    const double u = h[0] * px_ + h[1] * py_ + h[2];
    const double v = h[3] * px_ + h[4] * py_ + h[5];
    const double w = h[6] * px_ + h[7] * py_ + 1.0;
    r[0] = (u / w - qx_) * to_px_forward_;
    r[1] = (v / w - qy_) * to_px_forward_;
    // Backward: (U / W, V / W) against p, with adj(H) = [a b c; d e f; g k l].
    const double a = h[4] - h[5] * h[7], b = h[2] * h[7] - h[1], c = h[1] * h[5] - h[2] * h[4];
    const double d = h[5] * h[6] - h[3], e = h[0] - h[2] * h[6], f = h[2] * h[3] - h[0] * h[5];
    const double g = h[3] * h[7] - h[4] * h[6], k = h[1] * h[6] - h[0] * h[7], l = h[0] * h[4] - h[1] * h[3];
    const double U = a * qx_ + b * qy_ + c;
    const double V = d * qx_ + e * qy_ + f;
    const double W = g * qx_ + k * qy_ + l;
    r[2] = (U / W - px_) * to_px_backward_;
    r[3] = (V / W - py_) * to_px_backward_;
    if (jacobians == nullptr || jacobians[0] == nullptr) return true;

    double* J = jacobians[0];  // row-major 4 x 8
    const double sf = to_px_forward_ / w, x = u / w, y = v / w;
    const double forward_u[8] = {px_, py_, 1.0, 0, 0, 0, -x * px_, -x * py_};
    const double forward_v[8] = {0, 0, 0, px_, py_, 1.0, -y * px_, -y * py_};
    // d(U, V, W) / dh, from the adjugate's entries above.
    const double dU[8] = {0, h[5] - qy_, h[7] * qy_ - h[4], 0, qx_ - h[2], h[1] - h[7] * qx_, 0, h[2] * qy_ - h[5] * qx_};
    const double dV[8] = {qy_ - h[5], 0, h[3] - h[6] * qy_, h[2] - qx_, 0, h[6] * qx_ - h[0], h[5] * qx_ - h[2] * qy_, 0};
    const double dW[8] = {h[4] - h[7] * qy_, h[6] * qy_ - h[3], 0, h[7] * qx_ - h[1],
                          h[0] - h[6] * qx_, 0, h[1] * qy_ - h[4] * qx_, h[3] * qx_ - h[0] * qy_};
    const double sb = to_px_backward_ / W, X = U / W, Y = V / W;
    for (int j = 0; j < 8; ++j) {
      J[j] = sf * forward_u[j];
      J[8 + j] = sf * forward_v[j];
      J[16 + j] = sb * (dU[j] - X * dW[j]);
      J[24 + j] = sb * (dV[j] - Y * dW[j]);
    }
    return true;
  }

 private:
  double px_, py_, qx_, qy_;
  double to_px_forward_, to_px_backward_;  // undo the normalisation scale of each image
};

}  // namespace uavmot::motion
