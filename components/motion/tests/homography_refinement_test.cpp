// The Ceres refinement earns its place: on noisy correspondences contaminated by small independent
// motions (vehicles moving less than the RANSAC threshold, so they end up as inliers), it lowers
// the error of the robust estimate alone.
#include <cstdio>

#include <ceres/autodiff_cost_function.h>
#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "homography_estimation.hpp"
#include "homography_refinement.hpp"
#include "symmetric_transfer_error.hpp"
#include "uavmot/core/homography.hpp"

namespace uavmot::motion {
namespace {

const cv::Size kSize(1920, 1080);

Homography camera_motion(cv::RNG& rng) {
  const double a = rng.uniform(-0.3, 0.3) * M_PI / 180.0;
  const double s = 1.0 + rng.uniform(-0.003, 0.003);
  Homography h(s * std::cos(a), -s * std::sin(a), rng.uniform(-20.0, 20.0), s * std::sin(a), s * std::cos(a),
               rng.uniform(-20.0, 20.0), rng.uniform(-2e-6, 2e-6), rng.uniform(-2e-6, 2e-6), 1.0);
  return h;
}

struct Correspondences {
  std::vector<cv::Point2f> src, dst;
};

// 800 points; Gaussian noise; 20% on "vehicles" displaced 0.4-1.2 px in a common direction
// per vehicle (within the 1.5 px RANSAC threshold); 5% gross mismatches.
Correspondences make_data(const Homography& h, double noise_px, cv::RNG& rng) {
  Correspondences c;
  std::vector<cv::Vec2d> vehicle_motion;
  for (int v = 0; v < 8; ++v) {
    const double speed = rng.uniform(0.4, 1.2), dir = rng.uniform(0.0, 2 * M_PI);
    vehicle_motion.emplace_back(speed * std::cos(dir), speed * std::sin(dir));
  }
  for (int i = 0; i < 800; ++i) {
    const cv::Point2d p(rng.uniform(10.0, kSize.width - 10.0), rng.uniform(10.0, kSize.height - 10.0));
    cv::Point2d q = apply_homography(h, p);
    const double kind = rng.uniform(0.0, 1.0);
    if (kind < 0.20) {
      const cv::Vec2d m = vehicle_motion[static_cast<size_t>(rng.uniform(0, 8))];
      q += cv::Point2d(m[0], m[1]);
    } else if (kind < 0.25) {
      q += cv::Point2d(rng.uniform(-30.0, 30.0), rng.uniform(-30.0, 30.0));
    }
    q += cv::Point2d(rng.gaussian(noise_px), rng.gaussian(noise_px));
    c.src.emplace_back(static_cast<float>(p.x), static_cast<float>(p.y));
    c.dst.emplace_back(static_cast<float>(q.x), static_cast<float>(q.y));
  }
  return c;
}

void compare(const std::string& method, double noise_px) {
  MotionOptions o;
  o.robust_method = method;
  cv::RNG rng(1234);
  double robust_sum = 0, refined_sum = 0;
  int refined_better = 0;
  const int trials = 30;
  for (int t = 0; t < trials; ++t) {
    const Homography truth = camera_motion(rng);
    const Correspondences c = make_data(truth, noise_px, rng);
    const RobustHomography robust = estimate_robust_homography(c.src, c.dst, kSize, o);
    ASSERT_TRUE(robust.ok) << robust.failure;
    const Homography refined = refine_homography(robust.h, c.src, c.dst, robust.inliers, o);
    const double e_robust = mean_transfer_error(robust.h, truth, kSize.width, kSize.height);
    const double e_refined = mean_transfer_error(refined, truth, kSize.width, kSize.height);
    robust_sum += e_robust;
    refined_sum += e_refined;
    refined_better += e_refined < e_robust ? 1 : 0;
  }
  std::printf("%s, noise %.2f px: mean transfer error robust only %.4f px, with Ceres %.4f px (better in %d/%d)\n",
              method.c_str(), noise_px, robust_sum / trials, refined_sum / trials, refined_better, trials);
  EXPECT_LT(refined_sum, 0.8 * robust_sum) << method;
  EXPECT_GE(refined_better, trials * 2 / 3) << method;
}

TEST(HomographyRefinement, CeresLowersErrorOfRansac) { compare("ransac", 0.3); }
TEST(HomographyRefinement, CeresLowersErrorOfMagsac) { compare("magsac", 0.3); }

// The same residuals differentiated by Ceres's jets: the written-out derivatives must agree.
struct AutoDiffTransferError {
  double px, py, qx, qy, sf, sb;
  template <typename T>
  bool operator()(const T* const h, T* r) const {
    const T w = h[6] * px + h[7] * py + T(1.0);
    r[0] = ((h[0] * px + h[1] * py + h[2]) / w - qx) * sf;
    r[1] = ((h[3] * px + h[4] * py + h[5]) / w - qy) * sf;
    const T a = h[4] - h[5] * h[7], b = h[2] * h[7] - h[1], c = h[1] * h[5] - h[2] * h[4];
    const T d = h[5] * h[6] - h[3], e = h[0] - h[2] * h[6], f = h[2] * h[3] - h[0] * h[5];
    const T g = h[3] * h[7] - h[4] * h[6], k = h[1] * h[6] - h[0] * h[7], l = h[0] * h[4] - h[1] * h[3];
    const T wi = g * qx + k * qy + l;
    r[2] = ((a * qx + b * qy + c) / wi - px) * sb;
    r[3] = ((d * qx + e * qy + f) / wi - py) * sb;
    return true;
  }
};

TEST(HomographyRefinement, WrittenOutDerivativesMatchAutomaticDifferentiation) {
  cv::RNG rng(77);
  for (int trial = 0; trial < 200; ++trial) {
    double h[8];
    for (int i = 0; i < 8; ++i) h[i] = (i == 0 || i == 4) ? 1.0 + rng.uniform(-0.2, 0.2) : rng.uniform(-0.3, 0.3);
    h[6] *= 0.1;
    h[7] *= 0.1;
    const double px = rng.uniform(-1.5, 1.5), py = rng.uniform(-1.5, 1.5), qx = rng.uniform(-1.5, 1.5),
                 qy = rng.uniform(-1.5, 1.5), sf = rng.uniform(100.0, 900.0), sb = rng.uniform(100.0, 900.0);
    const SymmetricTransferError written(px, py, qx, qy, sf, sb);
    const ceres::AutoDiffCostFunction<AutoDiffTransferError, 4, 8> automatic(
        new AutoDiffTransferError{px, py, qx, qy, sf, sb});
    const double* parameters[1] = {h};
    double r_written[4], r_automatic[4], j_written[32], j_automatic[32];
    double* jw[1] = {j_written};
    double* ja[1] = {j_automatic};
    ASSERT_TRUE(written.Evaluate(parameters, r_written, jw));
    ASSERT_TRUE(automatic.Evaluate(parameters, r_automatic, ja));
    for (int i = 0; i < 4; ++i) EXPECT_NEAR(r_written[i], r_automatic[i], 1e-9 * (1.0 + std::abs(r_automatic[i])));
    for (int i = 0; i < 32; ++i) {
      EXPECT_NEAR(j_written[i], j_automatic[i], 1e-9 * (1.0 + std::abs(j_automatic[i])))
          << "trial " << trial << ", residual " << i / 8 << ", h" << i % 8;
    }
    // Residuals alone (no Jacobian asked) are the same values.
    double r_only[4];
    ASSERT_TRUE(written.Evaluate(parameters, r_only, nullptr));
    for (int i = 0; i < 4; ++i) EXPECT_EQ(r_only[i], r_written[i]);
  }
}

TEST(HomographyRefinement, ExactDataStaysExact) {
  cv::RNG rng(99);
  const Homography truth = camera_motion(rng);
  std::vector<cv::Point2f> src, dst;
  for (int i = 0; i < 100; ++i) {
    const cv::Point2d p(rng.uniform(0.0, 1920.0), rng.uniform(0.0, 1080.0));
    const cv::Point2d q = apply_homography(truth, p);
    src.emplace_back(static_cast<float>(p.x), static_cast<float>(p.y));
    dst.emplace_back(static_cast<float>(q.x), static_cast<float>(q.y));
  }
  Homography start = truth;
  start(0, 2) += 0.7;
  start(1, 2) -= 0.4;
  const Homography refined = refine_homography(start, src, dst, std::vector<unsigned char>(100, 1), MotionOptions{});
  EXPECT_LT(mean_transfer_error(refined, truth, 1920, 1080), 1e-3);
}

TEST(HomographyRefinement, TooFewPointsKeepsTheInitialEstimate) {
  const Homography h = Homography::eye();
  const std::vector<cv::Point2f> pts = {{1, 1}, {5, 5}, {9, 1}};
  EXPECT_EQ(refine_homography(h, pts, pts, {1, 1, 1}, MotionOptions{}), h);
}

}  // namespace
}  // namespace uavmot::motion
