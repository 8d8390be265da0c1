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

std::optional<PreviousFrameView> previous_frame_view(const ImageCrop& current, const OrientedBox& box, const ShiftSearch& search,
                                                     const Homography& previous_from_current,
                                                     const std::vector<ImageCrop>& previous) {
  const std::vector<cv::Point2d> shifts = shifts_to_try(search);
  if (shifts.empty() || !is_finite(box)) return std::nullopt;
  PreviousFrameView view;
  view.bounds = pixel_bounds(box) & current.roi;
  if (view.bounds.empty()) return std::nullopt;
  const cv::Point2d then = apply_homography(previous_from_current, cv::Point2d(view.bounds.x, view.bounds.y));
  view.source = window_holding(previous, cv::Rect2d(then, cv::Size2d(view.bounds.size())),
                               cv::Point2d(search.velocity[0], search.velocity[1]));
  if (view.source == nullptr) return std::nullopt;
  const cv::Matx22d jacobian = homography_jacobian(previous_from_current, cv::Point2d(box.cx, box.cy));
  for (const cv::Point2d& s : shifts) {
    const cv::Point2d o = -(jacobian * cv::Vec2d(s.x, s.y));
    view.offsets.push_back(o);
    view.lowest = {std::min(view.lowest.x, o.x), std::min(view.lowest.y, o.y)};
    view.highest = {std::max(view.highest.x, o.x), std::max(view.highest.y, o.y)};
  }
  return view;
}

// Exact, not an approximation: adding a larger offset never gives a smaller sum in floating point,
// and the window's test is one interval in x and one in y.
bool PreviousFrameView::holds_every_shift(const cv::Point2d& rest) const {
  return window_holds(*source, rest + lowest) && window_holds(*source, rest + highest);
}

std::optional<ShiftErrors> compare_shifts(const ImageCrop& current, const OrientedBox& box, const ShiftSearch& search,
                                          const Homography& previous_from_current, const std::vector<ImageCrop>& previous) {
  const auto view = previous_frame_view(current, box, search, previous_from_current, previous);
  if (!view) return std::nullopt;
  const cv::Rect& bounds = view->bounds;
  const ImageCrop* source = view->source;
  const std::vector<cv::Point2d>& offsets = view->offsets;
  const BoxFrame frame(box);
  int inside = 0;
  ShiftErrors e;
  std::vector<double> moved_error(offsets.size(), 0.0);
  for (int y = bounds.y; y < bounds.br().y; ++y) {
    const uint8_t* row = current.pixels.ptr<uint8_t>(y - current.roi.y);
    for (int x = bounds.x; x < bounds.br().x; ++x) {
      const cv::Point2d p(x, y);
      if (!frame.contains(p)) continue;
      ++inside;
      const cv::Point2d at_rest = apply_homography(previous_from_current, p);
      if (!view->holds_every_shift(at_rest)) continue;
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

bool moves_more_plainly(const ImageCrop& current, const OrientedBox& candidate, const std::optional<ShiftErrors>& reference,
                        const ShiftSearch& search, const Homography& previous_from_current,
                        const std::vector<ImageCrop>& previous) {
  const auto c = compare_shifts(current, candidate, search, previous_from_current, previous);
  if (!c || !(c->static_error > 0.0)) return false;
  if (!reference || !(reference->static_error > 0.0)) return true;
  return c->moving_error / c->static_error < reference->moving_error / reference->static_error;
}

}  // namespace uavmot::segmentation
