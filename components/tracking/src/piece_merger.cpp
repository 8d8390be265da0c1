#include "piece_merger.hpp"

#include <algorithm>
#include <cmath>

#include "split_merge.hpp"
#include "uavmot/core/spatial_grid.hpp"
#include "updater.hpp"

namespace uavmot::tracking {
namespace {

// Half extents of a box projected on a unit axis and on its normal. The pieces' own box angles are
// not trusted: a cab is near square, so its angle is noise; the common direction of travel is not.
struct Extent {
  double along = 0.0;
  double across = 0.0;
};

Extent extent_on(const OrientedBox& box, const cv::Point2d& axis) {
  const double a = box.angle_deg * CV_PI / 180.0;
  const double c = std::abs(std::cos(a) * axis.x + std::sin(a) * axis.y);  // |cos| of box axis vs axis
  const double s = std::sqrt(std::max(0.0, 1.0 - c * c));
  return {box.length / 2.0 * c + box.width / 2.0 * s, box.length / 2.0 * s + box.width / 2.0 * c};
}

struct PiecePair {
  cv::Point2d axis;    // direction of travel
  cv::Point2d offset;  // b's centre relative to a's: along, across the axis
  Extent a, b;
};

PiecePair measure(const OrientedBox& a, const OrientedBox& b, const cv::Vec2d& velocity) {
  PiecePair p;
  const double speed = cv::norm(velocity);
  p.axis = {velocity[0] / speed, velocity[1] / speed};
  const cv::Point2d normal(-p.axis.y, p.axis.x);
  const cv::Point2d d(b.cx - a.cx, b.cy - a.cy);
  p.offset = {d.dot(p.axis), d.dot(normal)};
  p.a = extent_on(a, p.axis);
  p.b = extent_on(b, p.axis);
  return p;
}

// The box along the direction of travel that holds both pieces.
OrientedBox union_along_axis(const OrientedBox& a, const PiecePair& p) {
  const double lo_u = std::min(-p.a.along, p.offset.x - p.b.along), hi_u = std::max(p.a.along, p.offset.x + p.b.along);
  const double lo_v = std::min(-p.a.across, p.offset.y - p.b.across), hi_v = std::max(p.a.across, p.offset.y + p.b.across);
  const double mid_u = (lo_u + hi_u) / 2.0, mid_v = (lo_v + hi_v) / 2.0;
  OrientedBox out;
  out.cx = a.cx + mid_u * p.axis.x - mid_v * p.axis.y;
  out.cy = a.cy + mid_u * p.axis.y + mid_v * p.axis.x;
  out.length = hi_u - lo_u;
  out.width = hi_v - lo_v;
  out.angle_deg = normalize_axis_angle_deg(std::atan2(p.axis.y, p.axis.x) * 180.0 / CV_PI);
  return out;
}

// Region hits after which a track's own Kalman velocity is trusted as its motion.
constexpr int kSettledHits = 10;

bool senior(const TrackRecord& a, const TrackRecord& b) { return a.hits != b.hits ? a.hits > b.hits : a.id < b.id; }

}  // namespace

bool pieces_move_as_one_body(const OrientedBox& a, const cv::Vec2d& motion_a, const OrientedBox& b,
                             const cv::Vec2d& motion_b, const TrackerOptions& options, const SceneInfo& scene) {
  const cv::Vec2d relative = motion_a - motion_b;
  const cv::Vec2d line(b.cx - a.cx, b.cy - a.cy);
  const double distance = cv::norm(line);
  if (!(distance > 1e-9)) return scene.speed_mps(cv::norm(relative)) <= options.piece_max_speed_difference_mps;
  // Two points of one rigid body keep their distance: their relative velocity lies across the line
  // between them, |omega| x distance for a body turning at omega. A car closing in on the one ahead
  // moves along that line.
  const double along = relative.dot(line) / distance;
  const double across = (relative[1] * line[0] - relative[0] * line[1]) / distance;
  const double turn_allowance_mps = options.piece_max_turn_rate_dps * CV_PI / 180.0 * scene.px_to_metres(distance);
  return scene.speed_mps(std::abs(along)) <= options.piece_max_speed_difference_mps &&
         scene.speed_mps(std::abs(across)) <= options.piece_max_speed_difference_mps + turn_allowance_mps;
}

bool are_pieces_of_one_object(const OrientedBox& a, const cv::Vec2d& motion_a, const OrientedBox& b,
                              const cv::Vec2d& motion_b, const TrackerOptions& options, const SceneInfo& scene) {
  if (!(options.piece_max_gap_m > 0.0)) return false;
  if (scene.speed_mps(cv::norm(motion_a)) < options.piece_min_speed_mps ||
      scene.speed_mps(cv::norm(motion_b)) < options.piece_min_speed_mps) {
    return false;
  }
  if (!pieces_move_as_one_body(a, motion_a, b, motion_b, options, scene)) return false;
  if (!(cv::norm(motion_a + motion_b) > 1e-9)) return false;  // no direction of travel (min speed 0)
  const PiecePair p = measure(a, b, motion_a + motion_b);
  // Each piece is one vehicle wide: a box over two cars side by side is no piece of anything.
  const double max_width = scene.metres_to_px(options.max_object_width_m);
  if (std::min(a.width, a.length) > max_width || std::min(b.width, b.length) > max_width) return false;
  // One behind the other in the same lane, not side by side or in the next lane.
  if (std::abs(p.offset.y) > scene.metres_to_px(options.piece_max_lateral_m)) return false;
  const double gap = std::abs(p.offset.x) - p.a.along - p.b.along;
  if (gap > scene.metres_to_px(options.piece_max_gap_m)) return false;
  const double length = std::abs(p.offset.x) + p.a.along + p.b.along;
  return length <= options.max_object_length_factor * scene.metres_to_px(scene.vehicle_length_m);
}

void merge_track_pieces(std::vector<TrackInFrame>& tracks, const FeatureIndex& features, const TrackerOptions& options,
                        const SceneInfo& scene) {
  const size_t n = tracks.size();
  if (!(options.piece_max_gap_m > 0.0)) return;
  // Each measured track's box and the motion of the features on it (precise to a few hundredths
  // of a pixel per frame, unlike a young track's Kalman velocity).
  std::vector<OrientedBox> boxes(n);
  std::vector<cv::Vec2d> motion(n);
  std::vector<bool> candidate(n, false);
  for (size_t i = 0; i < n; ++i) {
    if (!tracks[i].region_hit) continue;
    boxes[i] = box_of(tracks[i].kalman.mean);
    candidate[i] = region_motion(boxes[i], features, motion[i]);
    // A featureless piece (a dark bar across a trailer) moves as its filter says once that has settled.
    if (!candidate[i] && static_cast<int>(tracks[i].record.hits) >= kSettledHits) {
      motion[i] = velocity_of(tracks[i].kalman.mean);
      candidate[i] = true;
    }
  }
  // Only neighbours can be pieces of one object: a grid keeps the cost linear in the number of tracks.
  const double reach = scene.metres_to_px(options.piece_max_gap_m + options.max_object_width_m);
  SpatialGrid grid;
  for (size_t i = 0; i < n; ++i) {
    if (candidate[i]) grid.insert(static_cast<int>(i), axis_aligned_bounds(boxes[i]));
  }
  std::vector<bool> merged(n, false);
  const BoxMeasurementNoise noise = box_measurement_noise(options);
  for (size_t i = 0; i < n; ++i) {
    if (!candidate[i]) continue;
    for (const int k : grid.query_near(axis_aligned_bounds(boxes[i]), reach)) {
      const size_t j = static_cast<size_t>(k);
      if (merged[i]) break;
      if (j <= i || merged[j]) continue;
      const OrientedBox& a = boxes[i];
      const OrientedBox& b = boxes[j];
      const cv::Vec2d va = motion[i], vb = motion[j];
      if (!are_pieces_of_one_object(a, va, b, vb, options, scene)) continue;
      const size_t keeper = senior(tracks[i].record, tracks[j].record) ? i : j;
      const size_t piece = keeper == i ? j : i;
      const OrientedBox& kept_box = keeper == i ? a : b;
      const OrientedBox& piece_box = keeper == i ? b : a;
      const OrientedBox whole = union_along_axis(kept_box, measure(kept_box, piece_box, va + vb));
      KalmanState& kept = tracks[keeper].kalman;
      open_size_uncertainty(kept, whole);
      kept = update_with_box(kept, whole, noise, options.min_box_size_px);
      tracks[piece].absorbed = true;
      merged[i] = merged[j] = true;
    }
  }
}

}  // namespace uavmot::tracking
