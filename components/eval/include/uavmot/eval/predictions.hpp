#pragma once
// What a run produced, for scoring: boxes with track ids (or without, for segmentation
// regions), homographies and classified features. Filled from files (tracks.txt,
// tracks_obb.csv, homographies.txt, features.csv) or directly from the chain's data types.

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core/matx.hpp>
#include <opencv2/core/types.hpp>

#include "uavmot/core/chain_types.hpp"
#include "uavmot/core/homography.hpp"
#include "uavmot/core/oriented_box.hpp"
#include "uavmot/eval/sequence.hpp"

namespace uavmot::eval {

struct PredictedBox {
  int64_t id = -1;            // track id; -1 for boxes without identity (segmentation output)
  cv::Rect2d bounds;          // left, top, width, height (continuous)
  std::optional<OrientedBox> oriented;
  double confidence = 1.0;
};

struct PredictedFeature {
  uint64_t id = 0;
  cv::Point2d position;
  cv::Vec2d velocity;
  bool moving = false;
};

struct Predictions {
  std::map<int64_t, std::vector<PredictedBox>> boxes;  // frame -> boxes
  std::map<int64_t, Homography> homographies;          // frame -> estimated k-1 -> k
  std::map<int64_t, std::vector<PredictedFeature>> features;

  // Confirmed tracks (and, if asked, tentative/coasting ones) with their oriented boxes.
  void add_tracks(const TrackList& tracks, bool include_unconfirmed = false);
  // Boxes without identity, e.g. segmentation regions or feature clusters of one frame.
  void add_boxes(int64_t frame, const std::vector<OrientedBox>& boxes);
  // Regions of one segmentation method (paper Table I rows), or the feature clusters.
  void add_regions(const SegmentationResult& segmentation, SegmentationMethod method);
  void add_clusters(const SegmentationResult& segmentation);
  // The homography and classified features of one frame.
  void add_motion(const MotionEstimate& motion);
  bool has_identities() const;  // any box with id >= 0
};

struct PredictionFiles {
  std::string tracks;        // MOTChallenge tracks.txt (may be empty when `oriented` is given)
  std::string oriented;      // tracks_obb.csv: header with frame,id,cx,cy,width,length,angle_deg[,state]
  std::string homographies;  // frame,h11..h33
  std::string features;      // header frame,feature_id,x,y,vx,vy,moving
};

// Reads and validates the files; frames must lie in 1..info.length. Throws InputError naming
// the file and line of the first malformed or out-of-range record.
Predictions load_predictions(const PredictionFiles& files, const SequenceInfo& info);


}  // namespace uavmot::eval
