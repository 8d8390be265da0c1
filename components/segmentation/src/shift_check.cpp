#include "shift_check.hpp"

#include <algorithm>
#include <cmath>

#include "previous_window.hpp"

namespace uavmot::segmentation {

std::vector<cv::Point2d> shifts_to_try(const ShiftSearch& search) {
  const std::vector<double> steps =
      search.radius_px > 0.0 ? std::vector<double>{0.0, -search.radius_px, search.radius_px} : std::vector<double>{0.0};
  std::vector<cv::Point2d> shifts;
  for (const double dy : steps) {
    for (const double dx : steps) {
      const cv::Point2d s(search.velocity[0] + dx, search.velocity[1] + dy);
      if (std::hypot(s.x, s.y) >= search.min_speed_px) shifts.push_back(s);
    }
  }
  return shifts;
}

std::optional<ShiftErrors> compare_shifts(const ImageCrop& current, const OrientedBox& box, const ShiftSearch& search,
                                          const Homography& previous_from_current, const std::vector<ImageCrop>& previous) {
  const std::vector<cv::Point2d> shifts = shifts_to_try(search);
  const cv::Rect2d extent = axis_aligned_bounds(box);
  if (shifts.empty() || !(std::isfinite(extent.x) && std::isfinite(extent.y) && std::isfinite(extent.width) &&
                          std::isfinite(extent.height))) {
    return std::nullopt;
  }
  const cv::Rect bounds = pixel_bounds(box) & current.roi;
  if (bounds.empty()) return std::nullopt;
  // The previous window that holds most of the region at rest and moved (the window of the same
  // cluster, usually; a region at the edge of a cluster's window, as static texture beside a car
  // often is, may be held only in part, as the window moved with the car).
  const cv::Point2d then = apply_homography(previous_from_current, cv::Point2d(bounds.x, bounds.y));
  const ImageCrop* source = window_holding(previous, cv::Rect2d(then, cv::Size2d(bounds.size())),
                                           cv::Point2d(search.velocity[0], search.velocity[1]));
  if (source == nullptr) return std::nullopt;
  // Over a region's few pixels the homography is affine to well below a thousandth of a pixel:
  // each shift moves the previous-frame position by the same amount, the Jacobian times the shift.
  const cv::Matx22d jacobian = homography_jacobian(previous_from_current, cv::Point2d(box.cx, box.cy));
  std::vector<cv::Point2d> offsets;
  for (const cv::Point2d& s : shifts) offsets.push_back(-(jacobian * cv::Vec2d(s.x, s.y)));
  const BoxFrame frame(box);
  int inside = 0;
  ShiftErrors e;
  std::vector<double> moved_error(shifts.size(), 0.0);
  for (int y = bounds.y; y < bounds.br().y; ++y) {
    const uint8_t* row = current.pixels.ptr<uint8_t>(y - current.roi.y);
    for (int x = bounds.x; x < bounds.br().x; ++x) {
      const cv::Point2d p(x, y);
      if (!frame.contains(p)) continue;
      ++inside;
      const cv::Point2d at_rest = apply_homography(previous_from_current, p);
      bool held = window_holds(*source, at_rest);
      for (size_t i = 0; i < offsets.size() && held; ++i) held = window_holds(*source, at_rest + offsets[i]);
      if (!held) continue;
      const double value = row[x - current.roi.x];
      e.static_error += std::abs(value - sample_window(*source, at_rest));
      for (size_t i = 0; i < offsets.size(); ++i) moved_error[i] += std::abs(value - sample_window(*source, at_rest + offsets[i]));
      ++e.pixels;
    }
  }
  // Half the region at least, or the comparison says too little.
  if (e.pixels == 0 || 2 * e.pixels < inside) return std::nullopt;
  e.static_error /= e.pixels;
  e.moving_error = *std::min_element(moved_error.begin(), moved_error.end()) / e.pixels;
  return e;
}

bool moves_more_plainly(const ImageCrop& current, const OrientedBox& candidate, const OrientedBox& reference,
                        const ShiftSearch& search, const Homography& previous_from_current,
                        const std::vector<ImageCrop>& previous) {
  const auto c = compare_shifts(current, candidate, search, previous_from_current, previous);
  if (!c || !(c->static_error > 0.0)) return false;
  const auto r = compare_shifts(current, reference, search, previous_from_current, previous);
  if (!r || !(r->static_error > 0.0)) return true;
  return c->moving_error / c->static_error < r->moving_error / r->static_error;
}

}  // namespace uavmot::segmentation
