#include "homography_refinement.hpp"

#include <cmath>
#include <deque>
#include <memory>

#include <ceres/ceres.h>
#include <opencv2/core.hpp>

#include "symmetric_transfer_error.hpp"

namespace uavmot::motion {
namespace {

// Similarity that moves the centroid to 0 and the mean distance to sqrt(2) (Hartley).
cv::Matx33d normalising_transform(const std::vector<cv::Point2f>& points, const std::vector<unsigned char>& use) {
  double mx = 0, my = 0;
  int n = 0;
  for (size_t i = 0; i < points.size(); ++i) {
    if (!use[i]) continue;
    mx += points[i].x;
    my += points[i].y;
    ++n;
  }
  mx /= n;
  my /= n;
  double mean_distance = 0;
  for (size_t i = 0; i < points.size(); ++i) {
    if (use[i]) mean_distance += std::hypot(points[i].x - mx, points[i].y - my);
  }
  mean_distance /= n;
  const double s = mean_distance > 1e-9 ? std::sqrt(2.0) / mean_distance : 1.0;
  return {s, 0, -s * mx, 0, s, -s * my, 0, 0, 1};
}

// The loss acts on the squared norm of a point's 4 residuals, which are in pixels.
std::unique_ptr<ceres::LossFunction> make_loss(const MotionOptions& o) {
  if (o.refine_loss == "cauchy") return std::make_unique<ceres::CauchyLoss>(o.refine_loss_scale_px);
  if (o.refine_loss == "huber") return std::make_unique<ceres::HuberLoss>(o.refine_loss_scale_px);
  return nullptr;
}

}  // namespace

Homography refine_homography(const Homography& initial, const std::vector<cv::Point2f>& src,
                             const std::vector<cv::Point2f>& dst, const std::vector<unsigned char>& use,
                             const MotionOptions& o) {
  int n = 0;
  for (auto flag : use) n += flag ? 1 : 0;
  if (n < 4) return initial;
  // Every k-th usable point: keeps the spatial spread of the inliers, deterministic.
  const int stride = (n + o.refine_max_points - 1) / o.refine_max_points;
  const cv::Matx33d tp = normalising_transform(src, use);
  const cv::Matx33d tq = normalising_transform(dst, use);
  Homography hn = tq * initial * tp.inv();
  if (!normalize_homography(hn)) return initial;
  double params[8];
  for (int i = 0; i < 8; ++i) params[i] = hn.val[i];

  // The residual blocks live in one deque (cost functions cannot be moved), not one allocation
  // each; the problem is built here from finite values, so Ceres's safety checks are skipped.
  std::deque<SymmetricTransferError> costs;
  int seen = 0;
  for (size_t i = 0; i < src.size(); ++i) {
    if (!use[i] || seen++ % stride != 0) continue;
    const cv::Point3d p = tp * cv::Point3d(src[i].x, src[i].y, 1.0);
    const cv::Point3d q = tq * cv::Point3d(dst[i].x, dst[i].y, 1.0);
    costs.emplace_back(p.x, p.y, q.x, q.y, 1.0 / tq(0, 0), 1.0 / tp(0, 0));
  }
  ceres::Problem::Options problem_options;
  problem_options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  problem_options.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  problem_options.disable_all_safety_checks = true;
  ceres::Problem problem(problem_options);
  const auto loss = make_loss(o);
  for (SymmetricTransferError& cost : costs) problem.AddResidualBlock(&cost, loss.get(), params);
  ceres::Solver::Options solver_options;
  solver_options.linear_solver_type = ceres::DENSE_NORMAL_CHOLESKY;
  solver_options.num_threads = 1;
  solver_options.max_num_iterations = o.refine_max_iterations;
  solver_options.logging_type = ceres::SILENT;
  solver_options.minimizer_progress_to_stdout = false;
  solver_options.function_tolerance = 1e-12;
  solver_options.parameter_tolerance = 1e-12;
  ceres::Solver::Summary summary;
  ceres::Solve(solver_options, &problem, &summary);
  if (!summary.IsSolutionUsable()) return initial;

  Homography refined_n;
  for (int i = 0; i < 8; ++i) refined_n.val[i] = params[i];
  refined_n.val[8] = 1.0;
  Homography refined = tq.inv() * refined_n * tp;
  if (!normalize_homography(refined)) return initial;
  return refined;
}

}  // namespace uavmot::motion
