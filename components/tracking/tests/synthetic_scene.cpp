#include "synthetic_scene.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <opencv2/imgproc.hpp>

#include "split_merge.hpp"

namespace uavmot::tracking::testing {

CameraPath static_camera() {
  return [](int) { return identity_homography(); };
}

CameraPath moving_camera(cv::Vec2d translation, double rotation_deg, double zoom, cv::Point2d centre) {
  return [=](int frame) {
    const double k = frame - 1;
    const double a = rotation_deg * k * M_PI / 180.0;
    const double s = std::pow(zoom, k);
    // Rotate and zoom about the image centre, then translate.
    const cv::Matx33d to_origin(1, 0, -centre.x, 0, 1, -centre.y, 0, 0, 1);
    const cv::Matx33d rotate_scale(s * std::cos(a), -s * std::sin(a), 0, s * std::sin(a), s * std::cos(a), 0, 0, 0, 1);
    const cv::Matx33d back(1, 0, centre.x + translation[0] * k, 0, 1, centre.y + translation[1] * k, 0, 0, 1);
    return Homography(back * rotate_scale * to_origin);
  };
}

std::function<cv::Point2d(int)> straight(cv::Point2d start, cv::Vec2d velocity) {
  return [=](int frame) { return start + cv::Point2d(velocity[0], velocity[1]) * (frame - 1); };
}

std::function<cv::Point2d(int)> along_heading(cv::Point2d start, double speed, std::function<double(int)> heading_deg) {
  return [=](int frame) {
    cv::Point2d p = start;
    for (int k = 2; k <= frame; ++k) {
      const double a = heading_deg(k) * M_PI / 180.0;
      p += speed * cv::Point2d(std::cos(a), std::sin(a));
    }
    return p;
  };
}

Region piece_of(const Region& whole, double centre_u, double length) {
  Region piece = whole;
  const cv::Point2d centre = from_box_coordinates(whole.box, {centre_u, 0.0});
  piece.box.cx = centre.x;
  piece.box.cy = centre.y;
  piece.box.length = length;
  return piece;
}

SyntheticScene::SyntheticScene(std::vector<ObjectPath> objects, CameraPath camera, SceneOptions options)
    : objects_(std::move(objects)), camera_(std::move(camera)), options_(options), rng_(options.seed) {
  std::uniform_real_distribution<double> u(-0.45, 0.45);
  for (const auto& o : objects_) {
    std::vector<cv::Point2d> uvs;
    for (int j = 0; j < o.feature_count; ++j) uvs.emplace_back(u(rng_), u(rng_));
    feature_uv_.push_back(uvs);
  }
  std::uniform_real_distribution<double> ux(0.0, options_.image_width);
  std::uniform_real_distribution<double> uy(0.0, options_.image_height);
  for (int j = 0; j < options_.static_features; ++j) static_points_.emplace_back(ux(rng_), uy(rng_));
}

OrientedBox SyntheticScene::ground_box(const ObjectPath& o, int frame) const {
  const cv::Point2d c = o.ground_centre(frame);
  double heading = 0.0;
  if (o.heading_deg) {
    heading = o.heading_deg(frame);
  } else {
    const cv::Point2d d = o.ground_centre(frame + 1) - o.ground_centre(frame - 1);
    const auto it = last_heading_.find(o.truth_id);
    heading = cv::norm(d) > 1e-6 ? std::atan2(d.y, d.x) * 180.0 / M_PI : (it != last_heading_.end() ? it->second : 0.0);
  }
  return OrientedBox{c.x, c.y, o.width, o.length, normalize_axis_angle_deg(heading)};
}

SyntheticFrame SyntheticScene::next() {
  ++frame_;
  const int k = frame_;
  const Homography g = camera_(k);
  SyntheticFrame out;
  out.motion.frame_index = k;
  out.segmentation.frame_index = k;
  if (k > 1) {
    Homography h = g * camera_(k - 1).inv();
    normalize_homography(h);
    out.motion.homography = h;
  }
  out.motion.quality.valid = true;
  std::normal_distribution<double> n01(0.0, 1.0);
  auto inside_image = [&](const OrientedBox& b) {
    for (const auto& c : box_corners(b)) {
      if (c.x < 0 || c.y < 0 || c.x > options_.image_width || c.y > options_.image_height) return false;
    }
    return true;
  };
  for (size_t i = 0; i < objects_.size(); ++i) {
    const ObjectPath& o = objects_[i];
    const OrientedBox gb = ground_box(o, k);
    const OrientedBox gb_prev = ground_box(o, k - 1);
    last_heading_[o.truth_id] = gb.angle_deg;
    TruthBox t;
    t.id = o.truth_id;
    t.box = transform_box(g, gb);
    const cv::Point2d now = apply_homography(g, {gb.cx, gb.cy});
    const cv::Point2d before = apply_homography(g, {gb_prev.cx, gb_prev.cy});
    t.velocity = cv::Vec2d(now.x - before.x, now.y - before.y);
    t.visible = inside_image(t.box);
    t.moving = cv::norm(t.velocity) > options_.moving_speed_px;
    out.truth.push_back(t);
    if (!t.visible) continue;
    for (size_t j = 0; j < feature_uv_[i].size(); ++j) {
      const cv::Point2d uv = feature_uv_[i][j];
      const cv::Point2d p_now = apply_homography(g, from_box_coordinates(gb, uv));
      const cv::Point2d p_before = apply_homography(g, from_box_coordinates(gb_prev, uv));
      TrackedFeature f;
      f.id = o.truth_id * 1000 + j;
      f.position = p_now + cv::Point2d(n01(rng_), n01(rng_)) * options_.feature_position_noise_px;
      f.velocity = cv::Vec2d(p_now.x - p_before.x + n01(rng_) * options_.feature_velocity_noise,
                             p_now.y - p_before.y + n01(rng_) * options_.feature_velocity_noise);
      f.velocity_sigma = options_.feature_velocity_noise;
      f.age = static_cast<uint32_t>(k);
      f.moving = t.moving;
      out.motion.features.push_back(f);
    }
  }
  for (size_t j = 0; j < static_points_.size(); ++j) {
    TrackedFeature f;
    f.id = 900000 + j;
    f.position = static_points_[j];
    f.age = static_cast<uint32_t>(k);
    out.motion.features.push_back(f);
  }
  // Regions: one per visible moving object, or one per group of close objects when merging.
  std::vector<size_t> shown;
  for (size_t i = 0; i < out.truth.size(); ++i) {
    if (out.truth[i].visible && out.truth[i].moving) shown.push_back(i);
  }
  std::vector<size_t> group(out.truth.size());
  std::iota(group.begin(), group.end(), 0);
  std::function<size_t(size_t)> root = [&](size_t x) { return group[x] == x ? x : group[x] = root(group[x]); };
  if (options_.merge_close_objects) {
    for (size_t a = 0; a < shown.size(); ++a) {
      for (size_t b = a + 1; b < shown.size(); ++b) {
        OrientedBox ia = out.truth[shown[a]].box;
        OrientedBox ib = out.truth[shown[b]].box;
        ia.width += options_.merge_gap_px;
        ia.length += options_.merge_gap_px;
        if (intersection_area(ia, ib) > 0.0) group[root(shown[a])] = root(shown[b]);
      }
    }
  }
  std::map<size_t, std::vector<OrientedBox>> members;
  for (const size_t i : shown) members[root(i)].push_back(out.truth[i].box);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  for (const auto& [g_root, boxes] : members) {
    if (options_.region_miss_probability > 0.0 && u01(rng_) < options_.region_miss_probability) continue;
    OrientedBox b = boxes.size() == 1 ? boxes.front() : enclosing_box(boxes);
    b.cx += n01(rng_) * options_.region_centre_noise_px;
    b.cy += n01(rng_) * options_.region_centre_noise_px;
    b.width = std::max(1.0, b.width + n01(rng_) * options_.region_size_noise_px);
    b.length = std::max(1.0, b.length + n01(rng_) * options_.region_size_noise_px);
    b.angle_deg = normalize_axis_angle_deg(b.angle_deg + n01(rng_) * options_.region_angle_noise_deg);
    Region r;
    r.box = b;
    r.method = SegmentationMethod::Fusion;
    out.segmentation.regions.push_back(r);
  }
  for (int c = 0; c < options_.clutter_regions_per_frame; ++c) {
    Region r;
    r.box = OrientedBox{u01(rng_) * options_.image_width, u01(rng_) * options_.image_height, 3.0 + 4.0 * u01(rng_),
                        8.0 + 10.0 * u01(rng_), normalize_axis_angle_deg(360.0 * u01(rng_))};
    out.segmentation.regions.push_back(r);
  }
  if (edit_regions) edit_regions(k, out.segmentation.regions, out.truth);
  return out;
}

Score run_and_score(SyntheticScene& scene, Tracker& tracker, const RunOptions& run) {
  Score score;
  double pos_sum = 0.0;
  double width_sum = 0.0;
  double length_sum = 0.0;
  for (int k = 1; k <= run.frames; ++k) {
    SyntheticFrame f = scene.next();
    if (run.edit_motion) run.edit_motion(f.motion);
    const TrackList tracks = tracker.process(f.motion, f.segmentation);
    if (k < run.score_from_frame) continue;
    std::set<uint64_t> used;
    for (const auto& truth : f.truth) {
      if (!truth.visible || !truth.moving) continue;
      ++score.truth_instances;
      const Track* best = nullptr;
      double best_iou = run.min_iou;
      for (const auto& t : tracks.tracks) {
        if (t.state == TrackState::Tentative) continue;
        const double iou = intersection_over_union(t.box, truth.box);
        if (iou >= best_iou) {
          best_iou = iou;
          best = &t;
        }
      }
      if (best == nullptr) continue;
      ++score.matched;
      used.insert(best->id);
      const double e = cv::norm(cv::Point2d(best->box.cx - truth.box.cx, best->box.cy - truth.box.cy));
      pos_sum += e;
      score.max_position_error = std::max(score.max_position_error, e);
      width_sum += std::abs(best->box.width - truth.box.width);
      length_sum += std::abs(best->box.length - truth.box.length);
      auto& ids = score.track_ids_of_truth[truth.id];
      if (ids.empty() || ids.back() != best->id) ids.push_back(best->id);
    }
    for (const auto& t : tracks.tracks) {
      if (t.state == TrackState::Confirmed) score.all_confirmed_ids.insert(t.id);
      if (t.state == TrackState::Confirmed && !used.count(t.id)) ++score.unmatched_confirmed_tracks;
    }
  }
  if (score.matched > 0) {
    score.mean_position_error = pos_sum / score.matched;
    score.mean_width_error = width_sum / score.matched;
    score.mean_length_error = length_sum / score.matched;
  }
  return score;
}

}  // namespace uavmot::tracking::testing
