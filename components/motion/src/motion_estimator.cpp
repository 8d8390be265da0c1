#include "uavmot/motion/motion_estimator.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <mutex>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "background_flow.hpp"
#include "change_mask.hpp"
#include "creeping_features.hpp"
#include "dragged_feature.hpp"
#include "grid_corner_detector.hpp"
#include "homography_estimation.hpp"
#include "homography_refinement.hpp"
#include "image_contrast.hpp"
#include "klt_tracker.hpp"
#include "parallax_filter.hpp"
#include "relative_velocity.hpp"
#include "structure_edges.hpp"
#include "structure_patch.hpp"
#include "uavmot/core/checksum.hpp"
#include "uavmot/core/state_codec.hpp"

namespace uavmot::motion {
namespace {

// The contrast is read off every 8th row (and every 2nd column): a 99th percentile needs no more.
constexpr int kContrastRowStep = 8;

struct LiveFeature {
  uint64_t id = 0;
  cv::Point2f position;
  uint32_t age = 0;  // frames seen, 1 when detected
  FeatureHistory history;
  float corner_strength = 0.0f;  // its LK window's minimum eigenvalue this frame (min_corner_response units)
  VelocityEstimate velocity;
  MotionClassifier classifier;

  // Features are moved several times a frame (vector growth, the survivors' filters). cv::Vec's
  // copy constructor is not noexcept, which would make std::vector copy every history instead of
  // moving it; nothing here throws on a move.
  LiveFeature() = default;
  LiveFeature(const LiveFeature&) = default;
  LiveFeature(LiveFeature&&) noexcept = default;
  LiveFeature& operator=(const LiveFeature&) = default;
  LiveFeature& operator=(LiveFeature&&) noexcept = default;
};
static_assert(std::is_nothrow_move_constructible_v<LiveFeature>);

TrackedFeature to_output(const LiveFeature& f) {
  TrackedFeature out;
  out.id = f.id;
  out.position = cv::Point2d(f.position.x, f.position.y);
  out.velocity = f.velocity.velocity;
  out.velocity_sigma = f.velocity.sigma;
  out.age = f.age;
  out.moving = f.classifier.moving();
  return out;
}

// A feature as the parallax filter sees it, with the ground's image motion at its position under
// this frame's homography (what bounds the parallax of any static point there).
ParallaxSample parallax_sample(const LiveFeature& f, const Homography& h) {
  return {f.position, f.velocity.velocity, f.velocity.sigma, image_step_px(h, cv::Point2d(f.position))};
}

}  // namespace

struct PreparedFrame::Data {
  cv::Mat gray;
  Pyramid pyramid;
};
PreparedFrame::PreparedFrame() = default;
PreparedFrame::~PreparedFrame() = default;
PreparedFrame::PreparedFrame(PreparedFrame&&) noexcept = default;
PreparedFrame& PreparedFrame::operator=(PreparedFrame&&) noexcept = default;

class MotionEstimator::Impl {
 public:
  Impl(const MotionOptions& options, SceneInfo scene)
      : options_(resolved_for_scene(options, scene)),
        flat_scene_min_speed_px_(flat_scene_min_speed_px(options, scene)),
        scene_(scene),
        detector_(options_),
        parallax_(options_) {}

  // `prepared`: the frame's grey image and pyramid built ahead (the pyramid is swapped in), or null.
  MotionEstimate process(const Frame& frame, PreparedFrame::Data* prepared);
  void reset() {
    last_frame_index_ = 0;
    previous_ = Pyramid{};
    features_.clear();
    last_motion_ = Homography::eye();
    last_valid_ = false;
    detector_.reset();
    parallax_.reset();
  }
  const MotionOptions& options() const { return options_; }
  // prepare() builds into the buffers of a prepared frame process() has finished with, when there
  // is one: a pyramid allocated afresh every frame had its pages faulted in and zeroed by the kernel
  // every frame (at 4K, levels above glibc's 32 MB mmap threshold: more system time than the
  // pyramid's own build, and --threads 2 was slower than 1). Both run beside each other, hence the lock.
  std::unique_ptr<PreparedFrame::Data> take_recycled() const;
  void recycle(std::unique_ptr<PreparedFrame::Data> data) const;
  std::vector<uint8_t> save_state() const;
  void restore_state(const std::vector<uint8_t>& bytes);
  int64_t last_frame_index() const { return last_frame_index_; }
  const MotionStats& stats() const { return stats_; }

 private:
  // Tracks the live features into `current`; returns whether the frame pair gave a valid
  // homography (then the survivors replace features_).
  bool track_and_estimate(const Pyramid& current, MotionEstimate& out);
  void detect_new_features(const cv::Mat& gray, const Pyramid& current, bool continuous);

  MotionOptions options_;
  double flat_scene_min_speed_px_;  // the classifier's speed floor in frames without structure
  SceneInfo scene_;
  GridCornerDetector detector_;
  ParallaxFilter parallax_;
  MotionStats stats_;
  Pyramid previous_;
  Pyramid spare_;  // buffers for the next frame's pyramid
  mutable std::mutex recycled_mutex_;
  mutable std::unique_ptr<PreparedFrame::Data> recycled_;  // see take_recycled()
  std::vector<LiveFeature> features_;  // ordered by id
  uint64_t next_id_ = 1;
  Homography last_motion_ = Homography::eye();
  bool last_valid_ = false;
  int64_t last_frame_index_ = 0;
  cv::Mat gray_;
  double response_scale_ = 1.0;  // this frame's factor on min_corner_response (its contrast)
};

namespace {

// Why process() refuses `frame`, or an empty string.
std::string frame_problem(const Frame& frame, const MotionOptions& o) {
  if (frame.image.empty()) return "empty image";
  if (frame.image.type() != CV_8UC1 && frame.image.type() != CV_8UC3) {
    return "expected mono8 (CV_8UC1) or bgr8 (CV_8UC3), got OpenCV type " + std::to_string(frame.image.type());
  }
  const int min_side = 2 * o.border_px + o.lk_window_px;
  if (frame.image.cols < min_side || frame.image.rows < min_side) {
    return "image " + std::to_string(frame.image.cols) + "x" + std::to_string(frame.image.rows) + " is smaller than " +
           std::to_string(min_side) + " px";
  }
  return {};
}

cv::Mat gray_of(const Frame& frame) {
  if (frame.image.type() != CV_8UC3) return frame.image;
  cv::Mat gray;
  cv::cvtColor(frame.image, gray, cv::COLOR_BGR2GRAY);
  return gray;
}

}  // namespace

MotionEstimate MotionEstimator::Impl::process(const Frame& frame, PreparedFrame::Data* prepared) {
  if (const std::string problem = frame_problem(frame, options_); !problem.empty()) {
    throw InputError("frame " + std::to_string(frame.index) + " of stream '" + frame.stream_id + "': " + problem);
  }
  const bool use_prepared = prepared != nullptr && !prepared->pyramid.empty() && prepared->pyramid.size == frame.image.size();
  gray_ = use_prepared ? prepared->gray : gray_of(frame);

  MotionEstimate out;
  out.stream_id = frame.stream_id;
  out.frame_index = frame.index;
  out.capture_time_ns = frame.capture_time_ns;
  out.image_width = frame.image.cols;
  out.image_height = frame.image.rows;
  Pyramid& current = spare_;  // the buffers of the frame before the previous one
  if (use_prepared) {
    std::swap(current, prepared->pyramid);  // the old buffers leave with `prepared`
  } else {
    build_pyramid(gray_, options_, current);
  }

  response_scale_ = options_.contrast_reference_grey > 0.0
                        ? corner_response_scale(gradient_percentile(gray_, 99.0, kContrastRowStep),
                                                options_.contrast_reference_grey, options_.contrast_min_scale)
                        : 1.0;
  const bool valid = track_and_estimate(current, out);
  if (!valid) features_.clear();  // nothing links this frame to the last: every feature restarts
  last_valid_ = valid;
  last_motion_ = valid ? out.homography : Homography::eye();

  detect_new_features(gray_, current, valid);
  std::swap(previous_, spare_);
  gray_.release();  // never keep a reference to the caller's buffer
  last_frame_index_ = frame.index;

  out.features.reserve(features_.size());
  for (const auto& f : features_) out.features.push_back(to_output(f));
  return out;
}

bool MotionEstimator::Impl::track_and_estimate(const Pyramid& current, MotionEstimate& out) {
  if (previous_.empty() || previous_.size != current.size || features_.empty()) return false;
  const MotionOptions& o = options_;
  std::vector<cv::Point2f> from;
  from.reserve(features_.size());
  for (const auto& f : features_) from.push_back(f.position);

  // One tracking attempt from the initial positions `guess`; true when it gives a usable homography.
  std::vector<cv::Point2f> src, dst;
  std::vector<size_t> index;  // into features_
  std::vector<float> strength;  // per tracked feature, as src
  RobustHomography robust;
  auto attempt = [&](const std::vector<cv::Point2f>& guess, int levels) {
    std::vector<cv::Point2f> to;
    std::vector<unsigned char> tracked;
    std::vector<float> strengths;
    track_features(previous_, current, from, guess, levels, o, to, tracked, strengths);
    src.clear();
    dst.clear();
    index.clear();
    strength.clear();
    for (size_t i = 0; i < features_.size(); ++i) {
      if (!tracked[i]) continue;
      src.push_back(from[i]);
      dst.push_back(to[i]);
      index.push_back(i);
      strength.push_back(strengths[i]);
    }
    if (static_cast<double>(src.size()) < o.min_tracked_ratio * static_cast<double>(features_.size())) {
      robust = RobustHomography{};
      return false;
    }
    robust = estimate_robust_homography(src, dst, current.size, o);
    return robust.ok;
  };

  std::vector<cv::Point2f> guess = from;
  if (o.predict_with_previous_homography && last_valid_) {
    for (auto& p : guess) {
      const cv::Point2d q = apply_homography(last_motion_, cv::Point2d(p));
      p = cv::Point2f(static_cast<float>(q.x), static_cast<float>(q.y));
    }
  }
  bool ok = attempt(guess, o.lk_quick_levels);
  if (!ok && o.lk_quick_levels < o.pyramid_levels) ok = attempt(guess, o.pyramid_levels);
  if (!ok && o.recover_large_motion) {
    // The camera jumped (dropped frames, a jerk): start again from a coarse global translation.
    bool confident = false;
    const cv::Point2d shift = coarse_translation(previous_, current, confident);
    if (confident) {
      for (size_t i = 0; i < from.size(); ++i) {
        guess[i] = from[i] + cv::Point2f(static_cast<float>(shift.x), static_cast<float>(shift.y));
      }
      ok = attempt(guess, o.pyramid_levels);
    }
  }
  if (!ok) return false;

  Homography h = robust.h;
  if (o.refine) {
    // Features already known to move are not background: keep them out of the refinement
    // unless that leaves too few points.
    std::vector<unsigned char> use = robust.inliers;
    if (o.refine_exclude_moving) {
      int kept = 0;
      std::vector<unsigned char> background = use;
      for (size_t k = 0; k < background.size(); ++k) {
        if (background[k] && features_[index[k]].classifier.moving()) background[k] = 0;
        kept += background[k];
      }
      if (kept >= o.min_inliers) use = std::move(background);
    }
    const Homography refined = refine_homography(h, src, dst, use, o);
    if (plausible_motion(refined, current.size, o, nullptr)) h = refined;
  }
  out.homography = h;
  out.quality.valid = true;
  out.quality.inliers = static_cast<uint32_t>(robust.inlier_count);
  out.quality.residual_px = rms_transfer_error(h, src, dst, robust.inliers);

  std::vector<LiveFeature> survivors;
  std::vector<cv::Point2f> survivors_from;  // where each survivor was in the previous frame
  survivors.reserve(index.size());
  for (size_t k = 0; k < index.size(); ++k) {
    if (is_tracking_slip(h, src[k], dst[k], features_[index[k]].velocity, o.max_step_error_px)) continue;
    survivors_from.push_back(src[k]);
    LiveFeature f = std::move(features_[index[k]]);
    f.position = dst[k];
    f.corner_strength = strength[k];
    ++f.age;
    f.history.carry_forward(h);
    f.history.push(f.position, o.history_frames);
    f.velocity = estimate_velocity(f.history, o);
    survivors.push_back(std::move(f));
  }
  // Remove the smooth residual field of the background (lens distortion, relief) before deciding.
  BackgroundFlow flow(o.background_flow_degree, current.size);
  std::vector<cv::Point2f> positions;
  std::vector<cv::Vec2d> velocities;
  for (const auto& f : survivors) {
    if (f.history.size() < o.min_track_frames) continue;
    positions.push_back(f.position);
    velocities.push_back(f.velocity.velocity);
  }
  flow.fit(positions, velocities);
  std::vector<ParallaxSample> samples;
  samples.reserve(survivors.size());
  for (auto& f : survivors) {
    if (f.velocity.available) f.velocity.velocity -= flow.field(f.position);
    if (f.velocity.available && f.history.size() >= o.min_track_frames) samples.push_back(parallax_sample(f, h));
  }
  // Static 3-D structure moves along its epipolar line: that part is no independent motion. The
  // reported velocity stays relative to the ground plane; only the decision sees what is left.
  // The detector has run once per earlier frame since the estimator started or was reset.
  parallax_.fit(samples, current.size, out.frame_index, detector_.calls() + 1);
  std::vector<VelocityEstimate> decided(survivors.size());
  std::vector<double> speeds;
  speeds.reserve(survivors.size());
  for (size_t k = 0; k < survivors.size(); ++k) {
    const LiveFeature& f = survivors[k];
    decided[k] = f.velocity;
    if (!f.velocity.available) continue;
    decided[k].velocity = parallax_.independent_velocity(parallax_sample(f, h));
    if (f.history.size() >= o.min_track_frames) speeds.push_back(std::hypot(decided[k].velocity[0], decided[k].velocity[1]));
  }
  const double floor_px = scene_noise_floor(std::move(speeds), o);
  const StructureEdges edges(parallax_.supporters(), o);
  // The pixel floor guards mostly against parallax: a frame where no structure was found uses a
  // lower one (flat_scene_speed_factor), vehicles creeping in queues are above it.
  const bool structure_found = parallax_.model().valid || parallax_.model().provisional;
  ++stats_.decided_frames;
  if (structure_found) ++stats_.structure_frames;
  MotionOptions decision_options = o;
  if (!structure_found) decision_options.min_moving_speed_px = flat_scene_min_speed_px_;
  // One frame's velocity decides (MotionOptions::strong_motion_factor) only where it can be trusted:
  // not in a low-contrast frame, whose corners cannot place themselves well enough (lowsnr: twice
  // the false alarms), nor in one with 3-D structure, whose silhouettes slide (urban3d, oblique).
  // And only under a camera fast enough that a car is in view for few frames, where one frame of
  // latency is a share of its time in view worth that risk.
  const bool short_view = o.strong_motion_max_view_frames <= 0.0 ||
                          frames_to_cross_view(h, current.size) <= o.strong_motion_max_view_frames;
  if (response_scale_ < 1.0 || structure_found || !short_view) decision_options.strong_motion_factor = 0.0;
  const double faded_corner_threshold = o.faded_corner_ratio * o.min_corner_response * response_scale_;
  const Homography current_to_previous = h.inv();
  // No feature slower than this can be significant: the patch test spends its time on the rest.
  const double candidate_speed = o.release_ratio * std::max(decision_options.min_moving_speed_px, floor_px);
  const bool aperture_check =
      o.aperture_ratio > 0.0 && scene_.metres_to_px(scene_.vehicle_length_m) >= o.aperture_min_car_px;
  for (size_t k = 0; k < survivors.size(); ++k) {
    const LiveFeature& f = survivors[k];
    if (f.velocity.available) {
      const ParallaxSample sample = parallax_sample(f, h);
      // A corner on a roof's or crown's silhouette slides off its epipolar line: it does not start moving.
      decided[k].velocity = edges.decided_velocity(sample, decided[k].velocity, f.classifier.moving());
      // Pixels that static structure explains as well as the track does (structure_patch.hpp) do not
      // move this frame; a moving feature stops after confirm_frames such frames.
      ParallaxFilter::StructureMotion structure;
      if (o.structure_patch_ratio > 0.0 && std::hypot(decided[k].velocity[0], decided[k].velocity[1]) >= candidate_speed &&
          parallax_.structure_motion(sample, structure) &&
          structure_explains_patch(structure_patch_errors(previous_.levels[0], current.levels[0], survivors_from[k],
                                                          f.position, current_to_previous, structure,
                                                          o.structure_patch_radius_px),
                                   o)) {
        decided[k].velocity = cv::Vec2d(0.0, 0.0);
        ++stats_.structure_patch_holds;
      }
    }
    // A centre that is a line along its motion cannot show that motion: the rest of its window (a car
    // beside a lane marking) moves it.
    if (aperture_check && std::hypot(decided[k].velocity[0], decided[k].velocity[1]) >= candidate_speed &&
        centre_gradient_along(current.levels[0], f.position, decided[k].velocity, o) < o.aperture_ratio) {
      decided[k].velocity = cv::Vec2d(0.0, 0.0);
      ++stats_.aperture_holds;
    }
    // In a low-contrast frame a corner far below the threshold (noise on a weak corner, an edge it
    // slides along) cannot place itself to the precision the test needs: it does not start moving.
    if (response_scale_ < 1.0 && !f.classifier.moving() && f.corner_strength < faded_corner_threshold) {
      decided[k].velocity = cv::Vec2d(0.0, 0.0);
    }
  }
  // Cars creeping in queues: a lower floor where no faster neighbour says "dragged" (creeping_features.hpp).
  MotionOptions creep_options = decision_options;
  std::vector<unsigned char> creeping(survivors.size(), 0);
  if (!structure_found && response_scale_ >= 1.0 && o.creep_speed_factor < 1.0) {
    CreepRule rule;
    rule.floor_px = std::max(decision_options.min_moving_speed_px, floor_px);
    rule.creep_floor_px = std::max({o.creep_speed_factor * decision_options.min_moving_speed_px,
                                    decision_options.min_moving_speed_px - o.creep_max_drop_px, floor_px});
    rule.neighbour_radius_px = o.creep_neighbour_lengths * scene_.metres_to_px(scene_.vehicle_length_m);
    rule.neighbour_ratio = o.creep_neighbour_ratio;
    rule.min_support = o.creep_min_support;
    creep_options.min_moving_speed_px = rule.creep_floor_px;
    std::vector<cv::Point2f> where(survivors.size());
    std::vector<cv::Vec2d> velocity(survivors.size());
    std::vector<unsigned char> decidable(survivors.size(), 0);
    for (size_t k = 0; k < survivors.size(); ++k) {
      where[k] = survivors[k].position;
      velocity[k] = decided[k].velocity;
      decidable[k] = decided[k].available && survivors[k].history.size() >= o.min_track_frames;
    }
    creeping = creeping_features(where, velocity, decidable, rule);
  }
  for (size_t k = 0; k < survivors.size(); ++k) {
    survivors[k].classifier.update(decided[k], static_cast<int>(survivors[k].age), creeping[k] ? creep_options : decision_options,
                                   floor_px);
  }
  if (o.dragged_ratio > 0.0) {
    std::vector<LiveFeature> kept;
    kept.reserve(survivors.size());
    for (size_t k = 0; k < survivors.size(); ++k) {
      if (survivors[k].classifier.moving() &&
          centre_follows_background(previous_.levels[0], current.levels[0], survivors_from[k], survivors[k].position,
                                    current_to_previous, o)) {
        continue;  // dragged by the vehicle beside it: its own centre is ground
      }
      kept.push_back(std::move(survivors[k]));
    }
    survivors = std::move(kept);
  }
  features_ = std::move(survivors);
  return true;
}

void MotionEstimator::Impl::detect_new_features(const cv::Mat& gray, const Pyramid& current, bool continuous) {
  std::vector<cv::Point2f> existing;
  existing.reserve(features_.size());
  for (const auto& f : features_) existing.push_back(f.position);
  std::vector<cv::Point2f> found;
  const double car_length_px = scene_.metres_to_px(scene_.vehicle_length_m);
  const bool seed_on_change = options_.change_seed_features > 0 &&
                              (options_.change_seed_max_car_cells <= 0.0 ||
                               car_length_px < options_.change_seed_max_car_cells * detection_cell_size(options_, gray.size()));
  if (continuous && seed_on_change && !previous_.empty()) {
    // Before the grid fills the budget: what moves matters more than coverage (change_mask.hpp).
    // On the half-size level when a car is still change_min_vehicle_width_px wide there (each of
    // its pixels covers 2 x 2). Not coarser: a pixel of a coarser level marks a block of cells (on
    // the interlaced aphill FMV that lit up sheds and roofs).
    const bool half_size = current.levels.size() >= 4 && previous_.levels.size() >= 4 &&
                           scene_.metres_to_px(scene_.vehicle_width_m) / 2.0 >= options_.change_min_vehicle_width_px;
    const Homography half(0.5, 0, 0, 0, 0.5, 0, 0, 0, 1);  // full-size pixels to the level's (pyrDown)
    // levels[2]: the half-size image (buildOpticalFlowPyramid stores each level's derivatives after it).
    const cv::Mat changed = half_size ? changed_pixels(previous_.levels[2], current.levels[2], half * last_motion_ * half.inv(), options_)
                                      : changed_pixels(previous_.levels[0], gray, last_motion_, options_);
    const int scale = half_size ? 2 : 1;
    ChangeBlobs blobs(changed, options_.change_max_extent_lengths * car_length_px, scale);
    found = detect_changed_corners(gray, changed, existing, options_, options_.change_seed_features, &blobs, scale,
                                   current.picture);
    existing.insert(existing.end(), found.begin(), found.end());
  }
  const std::vector<cv::Point2f> grid =
      detector_.detect(gray, existing, continuous, response_scale_, last_motion_, current.picture);
  found.insert(found.end(), grid.begin(), grid.end());
  existing.insert(existing.end(), grid.begin(), grid.end());
  // Too few corners above the response to hold the homography on the ground (on `fastcam`, 30-110
  // per frame over a blurred field, the rest on the traffic, and the homography 1-20 px off): the
  // weaker corners serve too, in that frame only (docs/motion.md).
  if (options_.sparse_response_factor < 1.0 &&
      static_cast<double>(existing.size()) < options_.sparse_features_fraction * options_.max_features) {
    MotionOptions weaker = options_;
    weaker.min_corner_response *= options_.sparse_response_factor * response_scale_;
    const std::vector<cv::Point2f> weak = detect_missing_corners(gray, existing, weaker, current.picture);
    found.insert(found.end(), weak.begin(), weak.end());
  }
  for (const auto& p : found) {
    LiveFeature f;
    f.id = next_id_++;
    f.position = p;
    f.age = 1;
    f.history.push(p, options_.history_frames);
    features_.push_back(std::move(f));
  }
}


// ---- Saved state (save_state / restore_state) --------------------------------------------------
//
// File layout, little-endian: state_codec::seal's envelope around the payload:
//   magic "UMOTSTAT" (8 bytes) | u32 version | u64 payload bytes | u64 FNV-1a 64 of the payload | payload
// Payload (version 1):
//   u64 options fingerprint | i64 last frame index | u64 next id | bool last valid | 9 x f64 last homography
//   detector: i64 calls | i32 width | i32 height | u64 n | n x i64 retry_at
//   parallax: bool valid | 3 x f64 epipole | i32 side | i32 candidates | i32 support | f64 spread | f64 cap | i32 stable
//   previous grey image: i32 cols | i32 rows | cols*rows bytes (0 x 0: none)
//   u64 features, each: u64 id | f32 x | f32 y | u32 age | u64 n | n x (f64 x, f64 y) history |
//                       f64 vx | f64 vy | f64 sigma | bool available | bool moving | i32 streak
namespace {

constexpr char kStateMagic[8] = {'U', 'M', 'O', 'T', 'S', 'T', 'A', 'T'};
constexpr uint32_t kStateVersion = 1;
constexpr int kMaxStateImageSide = 1 << 15;

void put_string(state_codec::Writer& w, const std::string& s) {
  w.put(static_cast<uint64_t>(s.size()));
  w.put_bytes(s.data(), s.size());
}

// Every option (for_each_motion_option), as the estimator uses it (min_moving_speed_px includes
// the scene's ground speed): a state made under other options would not continue the same way.
uint64_t options_fingerprint(const MotionOptions& o) {
  state_codec::Writer w;
  for_each_motion_option(o, [&w](const char*, const auto& value, const auto&) {
    if constexpr (std::is_same_v<std::decay_t<decltype(value)>, std::string>) {
      put_string(w, value);
    } else {
      w.put(value);
    }
  });
  return fnv1a64(w.bytes().data(), w.bytes().size());
}

}  // namespace

std::vector<uint8_t> MotionEstimator::Impl::save_state() const {
  state_codec::Writer w;
  size_t feature_bytes = 0;
  for (const auto& f : features_) feature_bytes += 58 + 16 * f.history.positions().size();
  const size_t image_bytes = previous_.empty() ? 0 : previous_.size.area();
  w.reserve(256 + 8 * detector_.state().retry_at.size() + image_bytes + feature_bytes);
  w.put(options_fingerprint(options_));
  w.put(last_frame_index_);
  w.put(next_id_);
  w.put(last_valid_);
  for (double v : last_motion_.val) w.put(v);
  const GridCornerDetector::State detector = detector_.state();
  w.put(detector.calls);
  w.put(static_cast<int32_t>(detector.size.width));
  w.put(static_cast<int32_t>(detector.size.height));
  w.put(static_cast<uint64_t>(detector.retry_at.size()));
  for (int64_t v : detector.retry_at) w.put(v);
  const ParallaxModel& m = parallax_.model();
  w.put(m.valid);
  for (double v : m.epipole.val) w.put(v);
  w.put(static_cast<int32_t>(m.side));
  w.put(static_cast<int32_t>(m.candidates));
  w.put(static_cast<int32_t>(m.support));
  w.put(m.spread_px);
  w.put(m.cap_px);
  w.put(static_cast<int32_t>(m.stable_frames));
  // The previous pyramid's level 0 is the grey image itself (a copy, in a bordered buffer); the
  // pyramid is a function of it and the options, so the image is all that needs saving.
  const cv::Mat previous_gray = previous_.empty() ? cv::Mat() : previous_.levels[0];
  w.put(static_cast<int32_t>(previous_gray.cols));
  w.put(static_cast<int32_t>(previous_gray.rows));
  for (int y = 0; y < previous_gray.rows; ++y) w.put_bytes(previous_gray.ptr<uint8_t>(y), static_cast<size_t>(previous_gray.cols));
  w.put(static_cast<uint64_t>(features_.size()));
  for (const auto& f : features_) {
    w.put(f.id);
    w.put(f.position.x);
    w.put(f.position.y);
    w.put(f.age);
    w.put(static_cast<uint64_t>(f.history.positions().size()));
    for (const auto& p : f.history.positions()) {
      w.put(p.x);
      w.put(p.y);
    }
    w.put(f.velocity.velocity[0]);
    w.put(f.velocity.velocity[1]);
    w.put(f.velocity.sigma);
    w.put(f.velocity.available);
    w.put(f.classifier.moving());
    w.put(static_cast<int32_t>(f.classifier.streak()));
  }
  return state_codec::seal(kStateMagic, kStateVersion, w.bytes());
}

void MotionEstimator::Impl::restore_state(const std::vector<uint8_t>& bytes) {
  state_codec::Reader r = state_codec::unseal(bytes, kStateMagic, kStateVersion, "motion estimator state", "motion state");
  if (r.get<uint64_t>() != options_fingerprint(options_)) {
    r.fail("saved with other motion options or scene (gsd, fps) than this estimator's");
  }
  const auto frame_index = r.get<int64_t>();
  const auto next_id = r.get<uint64_t>();
  const bool last_valid = r.get<bool>();
  Homography last_motion;
  for (double& v : last_motion.val) v = r.get<double>();
  if (!is_finite(last_motion)) r.fail("the last homography is not finite");

  GridCornerDetector::State detector;
  detector.calls = r.get<int64_t>();
  detector.size.width = r.get<int32_t>();
  detector.size.height = r.get<int32_t>();
  const uint64_t cells = r.get_count(sizeof(int64_t));
  detector.retry_at.resize(cells);
  for (auto& v : detector.retry_at) v = r.get<int64_t>();
  if (detector.calls < 0 || detector.size.width < 0 || detector.size.height < 0) r.fail("the detector state is negative");

  ParallaxModel model;
  model.valid = r.get<bool>();
  for (double& v : model.epipole.val) v = r.get<double>();
  model.side = r.get<int32_t>();
  model.candidates = r.get<int32_t>();
  model.support = r.get<int32_t>();
  model.spread_px = r.get<double>();
  model.cap_px = r.get<double>();
  model.stable_frames = r.get<int32_t>();
  if (!std::isfinite(model.epipole[0]) || !std::isfinite(model.epipole[1]) || !std::isfinite(model.epipole[2]) ||
      !std::isfinite(model.spread_px) || !std::isfinite(model.cap_px) || model.side < -1 || model.side > 1) {
    r.fail("the parallax model is not finite or has an unknown side");
  }

  const auto cols = r.get<int32_t>();
  const auto rows = r.get<int32_t>();
  if (cols < 0 || rows < 0 || cols > kMaxStateImageSide || rows > kMaxStateImageSide || (cols == 0) != (rows == 0)) {
    r.fail("previous image of " + std::to_string(cols) + "x" + std::to_string(rows) + " px");
  }
  const int min_side = 2 * options_.border_px + options_.lk_window_px;
  if (cols > 0 && (cols < min_side || rows < min_side)) r.fail("previous image smaller than " + std::to_string(min_side) + " px");
  cv::Mat gray;
  if (cols > 0) {
    const uint8_t* pixels = r.get_bytes(static_cast<size_t>(cols) * static_cast<size_t>(rows));
    gray = cv::Mat(rows, cols, CV_8UC1, const_cast<uint8_t*>(pixels)).clone();
  }

  // A feature: at least its fixed fields (8 + 4 + 4 + 4 + 8 + 8 + 8 + 8 + 1 + 1 + 4 bytes).
  constexpr size_t kMinFeatureBytes = 58;
  const uint64_t count = r.get_count(kMinFeatureBytes);
  std::vector<LiveFeature> features(count);
  uint64_t last_id = 0;
  for (auto& f : features) {
    f.id = r.get<uint64_t>();
    if (f.id <= last_id || f.id >= next_id) r.fail("feature ids out of order or not below the next id");
    last_id = f.id;
    f.position.x = r.get<float>();
    f.position.y = r.get<float>();
    f.age = r.get<uint32_t>();
    const uint64_t n = r.get_count(16);
    if (n < 1 || n > static_cast<uint64_t>(std::max(1, options_.history_frames))) {
      r.fail("feature " + std::to_string(f.id) + " has " + std::to_string(n) + " history positions");
    }
    std::vector<cv::Point2d> history;
    history.reserve(n);
    for (uint64_t k = 0; k < n; ++k) {
      const double x = r.get<double>();
      const double y = r.get<double>();
      if (!std::isfinite(x) || !std::isfinite(y)) r.fail("feature " + std::to_string(f.id) + " has a non-finite history position");
      history.emplace_back(x, y);
    }
    f.history.restore(std::move(history));
    f.velocity.velocity[0] = r.get<double>();
    f.velocity.velocity[1] = r.get<double>();
    f.velocity.sigma = r.get<double>();
    f.velocity.available = r.get<bool>();
    const bool moving = r.get<bool>();
    const int streak = r.get<int32_t>();
    f.classifier.restore(moving, streak);
    if (!std::isfinite(f.position.x) || !std::isfinite(f.position.y) || f.age < 1 ||
        f.age > static_cast<uint32_t>(std::numeric_limits<int>::max())) {
      r.fail("feature " + std::to_string(f.id) + " has a non-finite position or an impossible age");
    }
    if (!std::isfinite(f.velocity.velocity[0]) || !std::isfinite(f.velocity.velocity[1]) ||
        !(f.velocity.sigma >= 0.0) || !std::isfinite(f.velocity.sigma) || streak < 0) {
      r.fail("feature " + std::to_string(f.id) + " has a non-finite velocity or a negative streak");
    }
  }
  if (r.remaining() != 0) r.fail(std::to_string(r.remaining()) + " bytes left over after the features");

  // Everything checked: only now does the estimator change.
  last_frame_index_ = frame_index;
  next_id_ = next_id;
  last_valid_ = last_valid;
  last_motion_ = last_motion;
  detector_.restore(std::move(detector));
  parallax_.restore(model);
  previous_ = Pyramid{};
  if (!gray.empty()) build_pyramid(gray, options_, previous_);
  features_ = std::move(features);
}

MotionEstimator::MotionEstimator(MotionOptions options, SceneInfo scene)
    : impl_(std::make_unique<Impl>(std::move(options), scene)) {}
MotionEstimator::~MotionEstimator() = default;
MotionEstimator::MotionEstimator(MotionEstimator&&) noexcept = default;
MotionEstimator& MotionEstimator::operator=(MotionEstimator&&) noexcept = default;

MotionEstimate MotionEstimator::process(const Frame& frame) { return impl_->process(frame, nullptr); }

std::unique_ptr<PreparedFrame::Data> MotionEstimator::Impl::take_recycled() const {
  const std::lock_guard lock(recycled_mutex_);
  return recycled_ ? std::move(recycled_) : std::make_unique<PreparedFrame::Data>();
}

void MotionEstimator::Impl::recycle(std::unique_ptr<PreparedFrame::Data> data) const {
  data->gray.release();  // never keep a reference to the caller's frame
  const std::lock_guard lock(recycled_mutex_);
  recycled_ = std::move(data);
}

PreparedFrame MotionEstimator::prepare(const Frame& frame) const {
  PreparedFrame prepared;
  if (!frame_problem(frame, impl_->options()).empty()) return prepared;  // process() says why
  prepared.data_ = impl_->take_recycled();
  prepared.data_->gray = gray_of(frame);
  build_pyramid(prepared.data_->gray, impl_->options(), prepared.data_->pyramid);
  return prepared;
}

MotionEstimate MotionEstimator::process(const Frame& frame, PreparedFrame prepared) {
  MotionEstimate out = impl_->process(frame, prepared.data_.get());
  if (prepared.data_) impl_->recycle(std::move(prepared.data_));  // now holding the buffers of two frames ago
  return out;
}
void MotionEstimator::reset() { impl_->reset(); }
std::vector<uint8_t> MotionEstimator::save_state() const { return impl_->save_state(); }
void MotionEstimator::restore_state(const std::vector<uint8_t>& bytes) { impl_->restore_state(bytes); }
int64_t MotionEstimator::last_frame_index() const { return impl_->last_frame_index(); }
const MotionOptions& MotionEstimator::options() const { return impl_->options(); }
const MotionStats& MotionEstimator::stats() const { return impl_->stats(); }

std::string describe_structure(const MotionStats& stats) {
  const std::string aperture =
      "; " + std::to_string(stats.aperture_holds) + " feature-frames held still on a line along their motion (aperture)";
  if (stats.structure_frames == 0) {
    return "no 3-D structure found (parallax steps idle in all " + std::to_string(stats.decided_frames) + " frames)" +
           aperture;
  }
  return "3-D structure (parallax) found in " + std::to_string(stats.structure_frames) + " of " +
         std::to_string(stats.decided_frames) + " frames; " + std::to_string(stats.structure_patch_holds) +
         " feature-frames held still by their pixels (structure patch)" + aperture;
}

}  // namespace uavmot::motion
