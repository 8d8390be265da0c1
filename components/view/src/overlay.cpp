#include "uavmot/view/overlay.hpp"

#include <algorithm>
#include <array>
#include <vector>
#include <cmath>

#include <fmt/format.h>
#include <opencv2/imgproc.hpp>

#include "uavmot/core/error.hpp"
#include "uavmot/core/oriented_box.hpp"

namespace uavmot::view {
namespace {

constexpr int kShift = 4;  // sub-pixel bits: lines land where the continuous coordinates say
constexpr double kOne = 1 << kShift;

// Maps continuous frame coordinates into the (scaled) output image, still continuous.
struct Canvas {
  cv::Mat image;
  double scale = 1.0;
  int thickness = 1;
  double font_scale = 0.4;

  cv::Point2d map(const cv::Point2d& p) const { return {(p.x + 0.5) * scale - 0.5, (p.y + 0.5) * scale - 0.5}; }
  static cv::Point fixed(const cv::Point2d& p) {
    return {static_cast<int>(std::lround(p.x * kOne)), static_cast<int>(std::lround(p.y * kOne))};
  }

  void line(const cv::Point2d& a, const cv::Point2d& b, const cv::Scalar& colour, int width) {
    cv::line(image, fixed(map(a)), fixed(map(b)), colour, width, cv::LINE_AA, kShift);
  }

  void dashed_line(const cv::Point2d& a, const cv::Point2d& b, const cv::Scalar& colour, int width) {
    const cv::Point2d pa = map(a), pb = map(b);
    const double length = cv::norm(pb - pa);
    const double dash = 4.0 * width + 2.0;
    const int pieces = std::max(1, static_cast<int>(length / dash));
    for (int i = 0; i < pieces; i += 2) {
      const cv::Point2d s = pa + (pb - pa) * (static_cast<double>(i) / pieces);
      const cv::Point2d e = pa + (pb - pa) * (static_cast<double>(std::min(i + 1, pieces)) / pieces);
      cv::line(image, fixed(s), fixed(e), colour, width, cv::LINE_AA, kShift);
    }
  }

  void box(const OrientedBox& b, const cv::Scalar& colour, int width, bool dashed = false) {
    const auto corners = box_corners(b);
    for (size_t i = 0; i < corners.size(); ++i) {
      const auto& a = corners[i];
      const auto& c = corners[(i + 1) % corners.size()];
      if (dashed) dashed_line(a, c, colour, width);
      else line(a, c, colour, width);
    }
  }

  void dot(const cv::Point2d& p, const cv::Scalar& colour) {
    cv::circle(image, fixed(map(p)), static_cast<int>(std::lround(std::max(1.0, 0.75 * thickness) * kOne)), colour,
               cv::FILLED, cv::LINE_AA, kShift);
  }

  void arrow(const cv::Point2d& from, const cv::Point2d& to, const cv::Scalar& colour) {
    const cv::Point2d a = map(from), b = map(to);
    const double length = cv::norm(b - a);
    // A fixed tip of a few pixels, whatever the arrow's length.
    const double tip = length > 0 ? std::min(0.5, (3.0 + 2.0 * thickness) / length) : 0.0;
    cv::arrowedLine(image, fixed(a), fixed(b), colour, thickness, cv::LINE_AA, kShift, tip);
  }

  // Text with a dark outline so it reads on any background; `anchor` is the bottom-left corner in
  // output pixels, moved inside the image.
  void text(const std::string& s, cv::Point anchor, const cv::Scalar& colour) {
    const int font = cv::FONT_HERSHEY_SIMPLEX;
    const int weight = std::max(1, static_cast<int>(std::lround(font_scale * 2.0)));
    int baseline = 0;
    const cv::Size size = cv::getTextSize(s, font, font_scale, weight + 2, &baseline);
    anchor.x = std::clamp(anchor.x, 1, std::max(1, image.cols - size.width - 1));
    anchor.y = std::clamp(anchor.y, size.height + 1, std::max(size.height + 1, image.rows - baseline - 1));
    cv::putText(image, s, anchor, font, font_scale, cv::Scalar(0, 0, 0), weight + 2, cv::LINE_AA);
    cv::putText(image, s, anchor, font, font_scale, colour, weight, cv::LINE_AA);
  }
};

bool finite(const cv::Point2d& p) { return std::isfinite(p.x) && std::isfinite(p.y); }
bool finite(const cv::Vec2d& v) { return std::isfinite(v[0]) && std::isfinite(v[1]); }

void draw_features(Canvas& canvas, const MotionEstimate& motion, const OverlayOptions& options) {
  // Stationary first, so moving vectors stay on top.
  if (options.stationary_features) {
    for (const auto& f : motion.features) {
      if (!f.moving && finite(f.position)) canvas.dot(f.position, kStationaryFeatureColour);
    }
  }
  if (!options.moving_features) return;
  for (const auto& f : motion.features) {
    if (!f.moving || !finite(f.position) || !finite(f.velocity)) continue;
    const cv::Point2d tip = f.position + cv::Point2d(f.velocity[0], f.velocity[1]) * options.vector_scale;
    canvas.arrow(f.position, tip, kMovingFeatureColour);
  }
}

// Where a label goes: centred above the box if free, else below it, else further out or to the
// side; never over an earlier label when any of those places is free (dense traffic would make
// them unreadable).
cv::Point place_label(const Canvas& canvas, const std::string& label, const cv::Rect2d& box, std::vector<cv::Rect>& taken,
                      bool& displaced) {
  int baseline = 0;
  const cv::Size size = cv::getTextSize(label, cv::FONT_HERSHEY_SIMPLEX, canvas.font_scale, 3, &baseline);
  const int centred = static_cast<int>(box.x + box.width / 2 - size.width / 2.0);
  const int above = static_cast<int>(box.y) - 3;
  const int below = static_cast<int>(box.y + box.height) + size.height + 3;
  const int step = size.height + baseline + 2;
  const std::array<int, 6> rows = {above, below, above - step, below + step, above - 2 * step, below + 2 * step};
  const std::array<int, 3> columns = {centred, centred + size.width / 2 + 4, centred - size.width / 2 - 4};
  auto rect_at = [&](int x, int y) { return cv::Rect(x, y - size.height - 1, size.width, size.height + baseline + 2); };
  displaced = false;
  for (const int y : rows) {
    for (const int x : columns) {
      const cv::Rect rect = rect_at(x, y);
      const bool inside = rect.y >= 0 && rect.y + rect.height <= canvas.image.rows && rect.x >= 0 &&
                          rect.x + rect.width <= canvas.image.cols;
      const bool free = std::none_of(taken.begin(), taken.end(), [&](const cv::Rect& r) { return (r & rect).area() > 0; });
      if (inside && free) {
        taken.push_back(rect);
        displaced = (y != above && y != below) || x != centred;
        return {x, y};
      }
    }
  }
  taken.push_back(rect_at(centred, above));
  return {centred, above};
}

void draw_tracks(Canvas& canvas, const TrackList& tracks, const OverlayOptions& options) {
  struct Label {
    std::string text;
    cv::Rect2d box;  // output pixels
  };
  std::vector<Label> labels;
  for (const auto& track : tracks.tracks) {
    if (!is_finite(track.box)) continue;
    const bool tentative = track.state == TrackState::Tentative;
    if (tentative && !options.tentative_tracks) continue;
    if (tentative) {
      canvas.box(track.box, kTentativeTrackColour, 1);
      continue;  // no label: most tentative tracks never confirm, labels would only clutter
    }
    const bool coasting = track.state == TrackState::Coasting;
    const int width = canvas.thickness + 1;
    canvas.box(track.box, coasting ? kCoastingTrackColour : kConfirmedTrackColour, width, coasting);
    const cv::Rect2d bounds = axis_aligned_bounds(track.box);
    const cv::Point2d top_left = canvas.map(bounds.tl()), bottom_right = canvas.map(bounds.br());
    labels.push_back({fmt::format("#{} {}", track.id, format_speed(track.velocity, options.gsd_m, options.fps)),
                      cv::Rect2d(top_left, bottom_right)});
  }
  // Labels after every box, so no box is drawn over a label.
  std::vector<cv::Rect> taken;
  for (const auto& label : labels) {
    bool displaced = false;
    const cv::Point at = place_label(canvas, label.text, label.box, taken, displaced);
    if (displaced) {
      // A thin leader from the label to its box, so a label pushed aside still points at its vehicle.
      const cv::Rect& rect = taken.back();
      const cv::Point2d centre(label.box.x + label.box.width / 2, label.box.y + label.box.height / 2);
      const cv::Point2d from(std::clamp(centre.x, double(rect.x), double(rect.x + rect.width)),
                             std::clamp(centre.y, double(rect.y), double(rect.y + rect.height)));
      cv::line(canvas.image, Canvas::fixed(from), Canvas::fixed(centre), kTentativeTrackColour, 1, cv::LINE_AA, kShift);
    }
    canvas.text(label.text, at, kConfirmedTrackColour);
  }
}

}  // namespace

std::string format_speed(const cv::Vec2d& velocity_px_per_frame, double gsd_m, double fps) {
  const double px_per_frame = std::hypot(velocity_px_per_frame[0], velocity_px_per_frame[1]);
  if (!std::isfinite(px_per_frame)) return "?";
  if (gsd_m > 0 && fps > 0) return fmt::format("{:.0f} km/h", px_per_frame * gsd_m * fps * 3.6);
  return fmt::format("{:.1f} px/f", px_per_frame);
}

std::string format_frame_label(int64_t index, double fps) {
  if (fps <= 0) return fmt::format("frame {}", index);
  return fmt::format("frame {}  {:.2f} s", index, static_cast<double>(index - 1) / fps);
}

cv::Mat draw_overlay(const cv::Mat& frame, const MotionEstimate* motion, const SegmentationResult* segmentation,
                     const TrackList* tracks, const OverlayOptions& options) {
  if (frame.empty()) throw InvalidArgument("draw_overlay: empty frame");
  if (frame.depth() != CV_8U || (frame.channels() != 1 && frame.channels() != 3)) {
    throw InvalidArgument("draw_overlay: frame must be 8-bit mono or BGR");
  }
  if (!(options.scale > 0) || !std::isfinite(options.scale)) throw InvalidArgument("draw_overlay: scale must be > 0");

  Canvas canvas;
  canvas.scale = options.scale;
  cv::Mat bgr;
  if (frame.channels() == 1) cv::cvtColor(frame, bgr, cv::COLOR_GRAY2BGR);
  else bgr = frame;
  if (options.scale == 1.0) {
    canvas.image = bgr.clone();
  } else {
    const cv::Size size(std::max(1, static_cast<int>(std::lround(frame.cols * options.scale))),
                        std::max(1, static_cast<int>(std::lround(frame.rows * options.scale))));
    cv::resize(bgr, canvas.image, size, 0, 0, options.scale > 1 ? cv::INTER_CUBIC : cv::INTER_AREA);
  }
  const int rows = canvas.image.rows;
  canvas.thickness = options.line_thickness > 0 ? options.line_thickness : std::max(1, static_cast<int>(std::lround(rows / 1000.0)));
  // Text ~8 px tall up to 768 lines, ~12 px from 1140 lines up: readable, not covering the traffic.
  canvas.font_scale = std::clamp(rows / 1900.0, 0.35, 0.6);

  if (motion) draw_features(canvas, *motion, options);
  if (segmentation && options.clusters) {
    for (const auto& c : segmentation->clusters) {
      if (is_finite(c.box)) canvas.box(c.box, kClusterColour, canvas.thickness);
    }
  }
  if (segmentation && options.regions) {
    for (const auto& r : segmentation->regions) {
      if (is_finite(r.box)) canvas.box(r.box, kRegionColour, canvas.thickness);
    }
  }
  if (tracks && options.tracks) draw_tracks(canvas, *tracks, options);

  if (options.frame_label) {
    int64_t index = 0;
    if (tracks) index = tracks->frame_index;
    else if (segmentation) index = segmentation->frame_index;
    else if (motion) index = motion->frame_index;
    if (index > 0) {
      const int line_height = static_cast<int>(std::lround(30 * canvas.font_scale)) + 4;
      canvas.text(format_frame_label(index, options.fps), cv::Point(6, line_height), cv::Scalar(255, 255, 255));
    }
  }
  return canvas.image;
}

}  // namespace uavmot::view
