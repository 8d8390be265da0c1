#include "uavmot/motion/motion_estimator.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "background_flow.hpp"
#include "grid_corner_detector.hpp"
#include "homography_estimation.hpp"
#include "homography_refinement.hpp"
#include "klt_tracker.hpp"
#include "parallax_filter.hpp"
#include "relative_velocity.hpp"

namespace uavmot::motion {
namespace {

struct LiveFeature {
  uint64_t id = 0;
  cv::Point2f position;
  uint32_t age = 0;  // frames seen, 1 when detected
  FeatureHistory history;
  VelocityEstimate velocity;
  MotionClassifier classifier;
};

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
  Impl(MotionOptions options, SceneInfo scene)
      : options_(std::move(options)), scene_(scene), detector_(options_), parallax_(options_) {
    validate(options_);
    if (options_.min_moving_speed_mps > 0.0) {
      if (!(scene_.gsd_m > 0.0) || !(scene_.fps > 0.0)) {
        throw InputError("motion options: min_moving_speed_mps needs a scene with gsd_m > 0 and fps > 0");
      }
      // One threshold in px/frame for the classifier: the stricter of the two.
      const double from_ground = options_.min_moving_speed_mps / (scene_.gsd_m * scene_.fps);
      options_.min_moving_speed_px = std::max(options_.min_moving_speed_px, from_ground);
    }
  }

  // `prepared`: the frame's grey image and pyramid built ahead (the pyramid is swapped in), or null.
  MotionEstimate process(const Frame& frame, PreparedFrame::Data* prepared);
  void reset() {
    previous_ = Pyramid{};
    features_.clear();
    last_motion_ = Homography::eye();
    last_valid_ = false;
    detector_.reset();
    parallax_.reset();
  }
  const MotionOptions& options() const { return options_; }

 private:
  // Tracks the live features into `current`; returns whether the frame pair gave a valid
  // homography (then the survivors replace features_).
  bool track_and_estimate(const Pyramid& current, MotionEstimate& out);
  void detect_new_features(const cv::Mat& gray, bool continuous);

  MotionOptions options_;
  SceneInfo scene_;
  GridCornerDetector detector_;
  ParallaxFilter parallax_;
  Pyramid previous_;
  Pyramid spare_;  // buffers for the next frame's pyramid
  std::vector<LiveFeature> features_;  // ordered by id
  uint64_t next_id_ = 1;
  Homography last_motion_ = Homography::eye();
  bool last_valid_ = false;
  cv::Mat gray_;
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

  const bool valid = track_and_estimate(current, out);
  if (!valid) features_.clear();  // nothing links this frame to the last: every feature restarts
  last_valid_ = valid;
  last_motion_ = valid ? out.homography : Homography::eye();

  detect_new_features(gray_, valid);
  std::swap(previous_, spare_);
  gray_.release();  // never keep a reference to the caller's buffer

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
  RobustHomography robust;
  auto attempt = [&](const std::vector<cv::Point2f>& guess) {
    std::vector<cv::Point2f> to;
    std::vector<unsigned char> tracked;
    track_features(previous_, current, from, guess, o, to, tracked);
    src.clear();
    dst.clear();
    index.clear();
    for (size_t i = 0; i < features_.size(); ++i) {
      if (!tracked[i]) continue;
      src.push_back(from[i]);
      dst.push_back(to[i]);
      index.push_back(i);
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
  bool ok = attempt(guess);
  if (!ok && o.recover_large_motion) {
    // The camera jumped (dropped frames, a jerk): start again from a coarse global translation.
    bool confident = false;
    const cv::Point2d shift = coarse_translation(previous_, current, confident);
    if (confident) {
      for (size_t i = 0; i < from.size(); ++i) {
        guess[i] = from[i] + cv::Point2f(static_cast<float>(shift.x), static_cast<float>(shift.y));
      }
      ok = attempt(guess);
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
  survivors.reserve(index.size());
  for (size_t k = 0; k < index.size(); ++k) {
    if (is_tracking_slip(h, src[k], dst[k], features_[index[k]].velocity, o.max_step_error_px)) continue;
    LiveFeature f = std::move(features_[index[k]]);
    f.position = dst[k];
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
    if (f.velocity.available && f.history.size() >= o.min_track_frames) samples.push_back({f.position, f.velocity.velocity, f.velocity.sigma});
  }
  // Static 3-D structure moves along its epipolar line: that part is no independent motion. The
  // reported velocity stays relative to the ground plane; only the decision sees what is left.
  parallax_.fit(samples, current.size, out.frame_index);
  std::vector<VelocityEstimate> decided(survivors.size());
  std::vector<double> speeds;
  speeds.reserve(survivors.size());
  for (size_t k = 0; k < survivors.size(); ++k) {
    const LiveFeature& f = survivors[k];
    decided[k] = f.velocity;
    if (!f.velocity.available) continue;
    decided[k].velocity = parallax_.independent_velocity({f.position, f.velocity.velocity, f.velocity.sigma});
    if (f.history.size() >= o.min_track_frames) speeds.push_back(std::hypot(decided[k].velocity[0], decided[k].velocity[1]));
  }
  const double floor_px = scene_noise_floor(std::move(speeds), o);
  for (size_t k = 0; k < survivors.size(); ++k) {
    LiveFeature& f = survivors[k];
    f.classifier.update(decided[k], static_cast<int>(f.age), o, floor_px);
  }
  features_ = std::move(survivors);
  return true;
}

void MotionEstimator::Impl::detect_new_features(const cv::Mat& gray, bool continuous) {
  std::vector<cv::Point2f> existing;
  existing.reserve(features_.size());
  for (const auto& f : features_) existing.push_back(f.position);
  for (const auto& p : detector_.detect(gray, existing, continuous)) {
    LiveFeature f;
    f.id = next_id_++;
    f.position = p;
    f.age = 1;
    f.history.push(p, options_.history_frames);
    features_.push_back(std::move(f));
  }
}

MotionEstimator::MotionEstimator(MotionOptions options, SceneInfo scene)
    : impl_(std::make_unique<Impl>(std::move(options), scene)) {}
MotionEstimator::~MotionEstimator() = default;
MotionEstimator::MotionEstimator(MotionEstimator&&) noexcept = default;
MotionEstimator& MotionEstimator::operator=(MotionEstimator&&) noexcept = default;

MotionEstimate MotionEstimator::process(const Frame& frame) { return impl_->process(frame, nullptr); }

PreparedFrame MotionEstimator::prepare(const Frame& frame) const {
  PreparedFrame prepared;
  if (!frame_problem(frame, impl_->options()).empty()) return prepared;  // process() says why
  prepared.data_ = std::make_unique<PreparedFrame::Data>();
  prepared.data_->gray = gray_of(frame);
  build_pyramid(prepared.data_->gray, impl_->options(), prepared.data_->pyramid);
  return prepared;
}

MotionEstimate MotionEstimator::process(const Frame& frame, PreparedFrame prepared) {
  return impl_->process(frame, prepared.data_.get());
}
void MotionEstimator::reset() { impl_->reset(); }
const MotionOptions& MotionEstimator::options() const { return impl_->options(); }

}  // namespace uavmot::motion
