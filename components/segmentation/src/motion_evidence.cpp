#include "motion_evidence.hpp"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

#include "previous_window.hpp"

namespace uavmot::segmentation {

std::optional<MotionEvidence> motion_evidence(const ImageCrop& current, const OrientedBox& box, double margin_px,
                                              const ShiftSearch& search, const Homography& previous_from_current,
                                              const std::vector<ImageCrop>& previous, double lengthen_px) {
  OrientedBox widened = box;
  widened.width += 2.0 * margin_px;
  widened.length += 2.0 * lengthen_px;
  const auto view = previous_frame_view(current, widened, search, previous_from_current, previous);
  if (!view) return std::nullopt;
  const cv::Rect& bounds = view->bounds;
  const ImageCrop* source = view->source;
  const std::vector<cv::Point2d>& offsets = view->offsets;

  // Whether pixel p of the widened box is held by the previous window at rest and under every
  // shift, and where it was at rest.
  const BoxFrame frame(widened), own(box);
  auto held_at = [&](const cv::Point2d& p, cv::Point2d& rest) {
    rest = apply_homography(previous_from_current, p);
    return view->holds_every_shift(rest);
  };
  auto grey_at = [&](int x, int y) { return static_cast<double>(current.pixels.at<uint8_t>(y - current.roi.y, x - current.roi.x)); };

  // The shift that explains the changed pixels best, i.e. takes away most of the error at rest.
  // Not the one with the least error overall: most of the widened box is static ground, which would
  // pick the slowest shift allowed. Every other pixel each way tells the shifts apart well enough
  // at a quarter of the cost.
  std::vector<double> explained(offsets.size(), 0.0);
  for (int y = bounds.y; y < bounds.br().y; y += 2) {
    for (int x = bounds.x; x < bounds.br().x; x += 2) {
      cv::Point2d rest;
      if (!frame.contains(cv::Point2d(x, y)) || !held_at(cv::Point2d(x, y), rest)) continue;
      const double value = grey_at(x, y), at_rest = std::abs(value - sample_window(*source, rest));
      for (size_t k = 0; k < offsets.size(); ++k) {
        explained[k] += std::max(0.0, at_rest - std::abs(value - sample_window(*source, rest + offsets[k])));
      }
    }
  }
  const auto best = static_cast<size_t>(std::max_element(explained.begin(), explained.end()) - explained.begin());

  // Per pixel: the error at rest less the error under that shift; pixels outside the widened box
  // or not held by the previous window stay at zero (no evidence either way).
  cv::Mat1f evidence = cv::Mat1f::zeros(bounds.size());
  cv::Mat1b counted = cv::Mat1b::zeros(bounds.size());
  int inside = 0, held_pixels = 0;
  for (int y = bounds.y; y < bounds.br().y; ++y) {
    for (int x = bounds.x; x < bounds.br().x; ++x) {
      const cv::Point2d p(x, y);
      if (!frame.contains(p)) continue;
      ++inside;
      cv::Point2d rest;
      if (!held_at(p, rest)) continue;
      const double value = grey_at(x, y);
      evidence(y - bounds.y, x - bounds.x) = static_cast<float>(std::abs(value - sample_window(*source, rest)) -
                                                                std::abs(value - sample_window(*source, rest + offsets[best])));
      counted(y - bounds.y, x - bounds.x) = 1;
      ++held_pixels;
    }
  }
  if (held_pixels == 0 || 2 * held_pixels < inside) return std::nullopt;
  // A pixel's error is noisy; its neighbourhood's says whether the shift explains it.
  cv::blur(evidence, evidence, cv::Size(3, 3), cv::Point(-1, -1), cv::BORDER_REPLICATE);
  double weight = 0.0, inside_weight = 0.0, sum_across = 0.0, sum_along = 0.0;
  const double angle = box.angle_deg * CV_PI / 180.0, across_sin = std::sin(angle), across_cos = std::cos(angle);
  for (int j = 0; j < evidence.rows; ++j) {
    for (int i = 0; i < evidence.cols; ++i) {
      if (!counted(j, i) || !(evidence(j, i) > 0.0f)) continue;
      const double w = evidence(j, i);
      const cv::Point2d p(bounds.x + i, bounds.y + j);
      weight += w;
      if (own.contains(p)) inside_weight += w;
      sum_across += w * (-(p.x - box.cx) * across_sin + (p.y - box.cy) * across_cos);
      sum_along += w * ((p.x - box.cx) * across_cos + (p.y - box.cy) * across_sin);
    }
  }
  if (!(weight > 0.0)) return std::nullopt;
  return MotionEvidence{sum_across / weight, inside_weight / weight, sum_along / weight};
}

}  // namespace uavmot::segmentation
