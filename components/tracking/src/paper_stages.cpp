// The paper's stages (section IV) behind the interfaces of stages.hpp, and make_stages().
// Each is a thin adapter: the algorithms are in the files named beside them.
#include <utility>

#include "initiator.hpp"
#include "piece_merger.hpp"
#include "split_merge.hpp"
#include "stages.hpp"
#include "track_update.hpp"

namespace uavmot::tracking {
namespace {

// region_associator: intersection over the smaller box above min_intersection_fraction.
class IntersectionGating final : public RegionAssociator {
 public:
  explicit IntersectionGating(double min_fraction) : min_fraction_(min_fraction) {}
  RegionAssociation associate(const std::vector<OrientedBox>& regions,
                              const std::vector<TrackInFrame>& tracks) const override {
    std::vector<OrientedBox> predicted;
    predicted.reserve(tracks.size());
    for (const auto& t : tracks) predicted.push_back(t.predicted);
    return associate_regions(regions, predicted, min_fraction_);
  }

 private:
  double min_fraction_;
};

// feature_associator: the four criteria.
class FourCriteriaFeatures final : public FeatureAssociator {
 public:
  FourCriteriaFeatures(const TrackerOptions& options, double min_search_length_px)
      : options_(options), min_search_length_px_(min_search_length_px) {}
  void prune(std::vector<TrackInFrame>& tracks, const FeatureIndex& features) const override {
    for (auto& t : tracks) prune_feature_links(t.record, t.predicted, t.velocity, t.velocity_known, features, options_);
  }
  void link(std::vector<TrackInFrame>& tracks, const FeatureIndex& features) const override {
    link_new_features(tracks, features, options_, min_search_length_px_);
  }

 private:
  TrackerOptions options_;
  double min_search_length_px_;
};

// split_merge and piece_merger.
class PaperSplitMerge final : public SplitMerge {
 public:
  PaperSplitMerge(const TrackerOptions& options, const SceneInfo& scene)
      : options_(options), scene_(scene), limits_(object_limits(options, scene)) {}
  std::vector<int> resolve(const RegionAssociation& gating, const FrameInput& input,
                           std::vector<TrackInFrame>& tracks) const override {
    SplitMergeResult r = resolve_split_merge(gating, input.regions, tracks, input.features, options_, limits_);
    for (size_t i = 0; i < tracks.size(); ++i) {
      tracks[i].measurement = std::move(r.measurements[i]);
      tracks[i].absorbed = r.absorbed[i];
    }
    return std::move(r.free_regions);
  }
  void merge_pieces(std::vector<TrackInFrame>& tracks, const FeatureIndex& features) const override {
    merge_track_pieces(tracks, features, options_, scene_);
  }

 private:
  TrackerOptions options_;
  SceneInfo scene_;
  ObjectLimits limits_;
};

// track_update: box, centre and feature-motion updates.
class KalmanUpdater final : public Updater {
 public:
  KalmanUpdater(const TrackerOptions& options, double vehicle_length_px)
      : options_(options), vehicle_length_px_(vehicle_length_px) {}
  void update(TrackInFrame& track, const FeatureIndex& features) const override {
    update_track(track, features, options_, vehicle_length_px_);
  }
  void commit(TrackInFrame& track, const FeatureIndex& features) const override {
    commit_update(track, features, options_.feature_uv_smoothing);
  }

 private:
  TrackerOptions options_;
  double vehicle_length_px_;
};

// initiator: free regions start tentative tracks or re-acquire dormant ones.
class PaperInitiator final : public Initiator {
 public:
  PaperInitiator(const TrackerOptions& options, const SceneInfo& scene) : options_(options), scene_(scene) {}
  void initiate(const std::vector<int>& free_regions, const FrameInput& input,
                const std::vector<OrientedBox>& live_boxes, TrackerState& state) const override {
    initiate_tracks(free_regions, input, live_boxes, options_, scene_, state);
  }

 private:
  TrackerOptions options_;
  SceneInfo scene_;
};

// Whether the camera uncovered the ground under `box` at most quick_confirm_max_ground_frames
// frames ago (its motion carried back).
bool on_new_ground(const OrientedBox& box, const FrameInput& in, const TrackerOptions& options) {
  const int max_frames = options.quick_confirm_max_ground_frames;
  if (max_frames < 0 || in.image.width <= 0 || in.image.height <= 0) return false;
  return frames_ground_in_view(in.homography, {box.cx, box.cy}, in.image, max_frames) <= max_frames;
}

// deleter: N-of-M confirmation, coasting, gaps, dormancy.
class PaperLifecycle final : public Deleter {
 public:
  PaperLifecycle(const TrackerOptions& options, double confirm_min_speed_px)
      : options_(options), confirm_min_speed_px_(confirm_min_speed_px) {}
  void age_dormant(TrackerState& state, const Homography& h) const override {
    tracking::age_dormant(state, h, options_);
  }
  Fate judge(TrackInFrame& track, const FrameInput& in) const override {
    const cv::Size& image = in.image;
    record_frame(track.record, track.region_hit, track.supported, options_, wholly_inside_view(track.posterior, image),
                 confirm_min_speed_px_, may_confirm_at(track.record, track.posterior, image, options_),
                 on_new_ground(track.posterior, in, options_));
    return decide_fate(track.record, inside_view(track.posterior, image), options_);
  }

 private:
  TrackerOptions options_;
  double confirm_min_speed_px_;
};

}  // namespace

TrackerStages make_stages(const TrackerOptions& options, const SceneInfo& scene) {
  const double vehicle_length_px = scene.metres_to_px(scene.vehicle_length_m);
  const double confirm_min_speed_px = scene.fps > 0.0 ? scene.metres_to_px(options.confirm_min_speed_mps) / scene.fps : 0.0;
  TrackerStages s;
  s.motion_model = make_motion_model(options);
  s.feature_associator = std::make_unique<FourCriteriaFeatures>(options, vehicle_length_px * options.link_min_length_factor);
  s.region_associator = std::make_unique<IntersectionGating>(options.min_intersection_fraction);
  s.split_merge = std::make_unique<PaperSplitMerge>(options, scene);
  s.updater = std::make_unique<KalmanUpdater>(options, vehicle_length_px);
  s.initiator = std::make_unique<PaperInitiator>(options, scene);
  s.deleter = std::make_unique<PaperLifecycle>(options, confirm_min_speed_px);
  return s;
}

}  // namespace uavmot::tracking
