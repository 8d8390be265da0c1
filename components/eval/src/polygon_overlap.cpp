#include "polygon_overlap.hpp"

#include <cmath>

namespace uavmot::eval::detail {
namespace {

double signed_area(const std::vector<cv::Point2d>& p) {
  double a = 0.0;
  for (size_t i = 0; i < p.size(); ++i) a += p[i].cross(p[(i + 1) % p.size()]);
  return a / 2.0;
}

}  // namespace

double polygon_area(const std::vector<cv::Point2d>& polygon) { return std::abs(signed_area(polygon)); }

double intersection_area(const OrientedBox& box, const std::vector<cv::Point2d>& convex) {
  if (convex.size() < 3) return 0.0;
  const auto corners = box_corners(box);
  std::vector<cv::Point2d> subject(corners.begin(), corners.end());
  // Sutherland-Hodgman: clip the box by each edge of the convex polygon; the polygon's own
  // orientation tells which side of an edge is inside.
  const double orientation = signed_area(convex) >= 0.0 ? 1.0 : -1.0;
  for (size_t i = 0; i < convex.size() && !subject.empty(); ++i) {
    const cv::Point2d a = convex[i], b = convex[(i + 1) % convex.size()];
    const auto side = [&](cv::Point2d p) { return orientation * (b - a).cross(p - a); };
    std::vector<cv::Point2d> out;
    for (size_t k = 0; k < subject.size(); ++k) {
      const cv::Point2d p = subject[k], q = subject[(k + 1) % subject.size()];
      const double sp = side(p), sq = side(q);
      if (sp >= 0.0) out.push_back(p);
      if ((sp >= 0.0) != (sq >= 0.0)) out.push_back(p + (q - p) * (sp / (sp - sq)));
    }
    subject = std::move(out);
  }
  return subject.size() < 3 ? 0.0 : polygon_area(subject);
}

}  // namespace uavmot::eval::detail
