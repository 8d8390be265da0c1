// Region gating, the four feature-assignment criteria, outlier removal and measurement reconstruction.
#include <gtest/gtest.h>

#include "feature_associator.hpp"
#include "region_associator.hpp"
#include "split_merge.hpp"

namespace uavmot::tracking {
namespace {

TrackedFeature feature(uint64_t id, cv::Point2d p, cv::Vec2d v, uint32_t age = 5) {
  TrackedFeature f;
  f.id = id;
  f.position = p;
  f.velocity = v;
  f.moving = true;
  f.age = age;
  return f;
}

std::vector<cv::Vec2d> velocities_of(size_t n) { return std::vector<cv::Vec2d>(n, cv::Vec2d(2, 0)); }

// The tracks as split/merge and feature linking see them in a frame: predicted at `predicted` with
// `velocities` (known), and for linking, updated with a region to the same box.
std::vector<TrackInFrame> in_frame(const std::vector<TrackRecord>& records, const std::vector<OrientedBox>& predicted,
                                   const std::vector<cv::Vec2d>& velocities, const std::vector<bool>& known = {}) {
  std::vector<TrackInFrame> tracks(records.size());
  for (size_t i = 0; i < records.size(); ++i) {
    tracks[i].record = records[i];
    tracks[i].predicted = tracks[i].posterior = predicted[i];
    tracks[i].velocity = velocities[i];
    tracks[i].velocity_known = known.empty() || known[i];
    tracks[i].region_hit = true;
  }
  return tracks;
}

// The limits split/merge handling gets from the scene: `single` object, `largest` object, `widest`
// region (zero: none).
ObjectLimits limits(cv::Size2d single = {}, cv::Size2d largest = {}, double widest = 0.0) {
  return ObjectLimits{single, largest, widest};
}

TEST(RegionAssociation, SmallOverlapValidatesNoOverlapDoesNot) {
  const OrientedBox track{100, 100, 5, 15, 0};
  EXPECT_TRUE(gate(OrientedBox{112, 100, 5, 15, 0}, track, 0.05));   // 3 px of 15 overlap: 20 %
  EXPECT_FALSE(gate(OrientedBox{114.6, 100, 5, 15, 0}, track, 0.05));  // 0.4 px: below 5 %
  EXPECT_FALSE(gate(OrientedBox{130, 100, 5, 15, 0}, track, 0.05));
}

TEST(RegionAssociation, DetectsMergeAndSplit) {
  const std::vector<OrientedBox> predictions = {{100, 100, 5, 15, 0}, {100, 106, 5, 15, 0}, {300, 300, 5, 15, 0}};
  // Region 0 covers tracks 0 and 1 (merge); regions 1 and 2 both lie on track 2 (split); region 3 is new.
  const std::vector<OrientedBox> regions = {{100, 103, 11, 15, 0}, {296, 300, 5, 7, 0}, {304, 300, 5, 7, 0}, {500, 50, 5, 15, 0}};
  const RegionAssociation a = associate_regions(regions, predictions, 0.05);
  EXPECT_EQ(a.tracks_of_region[0], (std::vector<int>{0, 1}));
  EXPECT_EQ(a.regions_of_track[2], (std::vector<int>{1, 2}));
  EXPECT_TRUE(a.tracks_of_region[3].empty());
}

class FeatureAssignment : public ::testing::Test {
 protected:
  void SetUp() override {
    tracks_.resize(2);
    tracks_[0].id = 1;
    tracks_[1].id = 2;
    predicted_ = {OrientedBox{100, 100, 6, 16, 0}, OrientedBox{112, 100, 6, 16, 0}};  // overlap for x in [104, 108]
    velocities_ = {cv::Vec2d(2, 0), cv::Vec2d(1, 0)};
  }
  void link(const std::vector<TrackedFeature>& fs, std::vector<bool> known = {true, true}) {
    const FeatureIndex index(fs);
    std::vector<TrackInFrame> frame = in_frame(tracks_, predicted_, velocities_, known);
    link_new_features(frame, index, options_, 0.0);
    for (size_t i = 0; i < tracks_.size(); ++i) tracks_[i] = frame[i].record;
  }
  std::vector<uint64_t> ids(size_t t) const {
    std::vector<uint64_t> out;
    for (const auto& l : tracks_[t].features) out.push_back(l.feature_id);
    return out;
  }
  TrackerOptions options_;
  std::vector<TrackRecord> tracks_;
  std::vector<OrientedBox> predicted_;
  std::vector<cv::Vec2d> velocities_;
};

TEST_F(FeatureAssignment, FourCriteria) {
  link({
      feature(1, {95, 100}, {2.0, 0.1}),   // inside track 1 only, same motion: linked
      feature(2, {97, 101}, {-1.0, 0.0}),  // inside track 1, opposite motion: criterion 4
      feature(3, {106, 100}, {2.0, 0.0}),  // inside both predictions: criterion 3
      feature(4, {115, 99}, {1.1, 0.0}),   // inside track 2 only: linked to track 2
      feature(5, {150, 100}, {2.0, 0.0}),  // inside no prediction: criterion 2
      feature(6, {93, 99}, {2.0, 1.5}),    // direction off by ~37 deg: criterion 4
  });
  EXPECT_EQ(ids(0), (std::vector<uint64_t>{1}));
  EXPECT_EQ(ids(1), (std::vector<uint64_t>{4}));
  // Criterion 1: a linked feature is not linked again, to this or another track.
  link({feature(1, {95, 100}, {2.0, 0.1}), feature(4, {115, 99}, {1.1, 0.0})});
  EXPECT_EQ(ids(0), (std::vector<uint64_t>{1}));
  EXPECT_EQ(ids(1), (std::vector<uint64_t>{4}));
}

TEST_F(FeatureAssignment, AtMostTwentyPerTrackOldestFirst) {
  std::vector<TrackedFeature> fs;
  for (uint64_t i = 0; i < 30; ++i) fs.push_back(feature(100 + i, {93.0 + 0.3 * i, 100.0}, {2.0, 0.0}, static_cast<uint32_t>(i)));
  link(fs);
  ASSERT_EQ(tracks_[0].features.size(), 20u);
  for (const auto& l : tracks_[0].features) EXPECT_GE(l.feature_id, 110u);  // the 20 oldest (age 10..29)
}

TEST_F(FeatureAssignment, StoresPositionOnTheBoxAndReconstructsTheCentre) {
  link({feature(1, {103, 101}, {2, 0}), feature(2, {96, 99}, {2, 0})});
  ASSERT_EQ(tracks_[0].features.size(), 2u);
  EXPECT_NEAR(tracks_[0].features[0].box_uv.x, 3.0 / 16.0, 1e-9);
  EXPECT_NEAR(tracks_[0].features[0].box_uv.y, 1.0 / 6.0, 1e-9);
  // The object moves by (3, -1): the features reconstruct the moved centre.
  const FeatureIndex moved({feature(1, {106, 100}, {2, 0}), feature(2, {99, 98}, {2, 0})});
  const auto centre = reconstruct_centre(tracks_[0], OrientedBox{102, 100, 6, 16, 0}, moved, 2);
  ASSERT_TRUE(centre.has_value());
  EXPECT_NEAR(centre->x, 103.0, 1e-9);
  EXPECT_NEAR(centre->y, 99.0, 1e-9);
  EXPECT_FALSE(reconstruct_centre(tracks_[0], predicted_[0], moved, 3).has_value());
}

TEST_F(FeatureAssignment, OutliersInPositionAndMotionAreRemoved) {
  link({feature(1, {94, 100}, {2, 0}), feature(2, {96, 100}, {2, 0}), feature(3, {98, 100}, {2, 0}),
        feature(4, {100, 101}, {2, 0}), feature(5, {102, 99}, {2, 0})});
  ASSERT_EQ(tracks_[0].features.size(), 5u);
  // Next frame: feature 2 jumped 4 px off its place on the object, feature 4 moves differently, feature 5 vanished.
  const FeatureIndex next({feature(1, {94, 100}, {2, 0}), feature(2, {96, 104}, {2, 0}), feature(3, {98, 100}, {2, 0}),
                           feature(4, {100, 101}, {0.2, 1.0})});
  prune_feature_links(tracks_[0], predicted_[0], velocities_[0], true, next, options_);
  std::vector<uint64_t> expected = {1, 3};
  EXPECT_EQ(ids(0), expected);
}

TEST_F(FeatureAssignment, LinkedVelocityIsTheMedianOfThePresentLinks) {
  tracks_[0].features = {FeatureLink{1, {0, 0}, 5}, FeatureLink{2, {0.1, 0}, 5}, FeatureLink{3, {-0.1, 0}, 5},
                         FeatureLink{4, {0.2, 0}, 5}};
  // Feature 4 vanished; of 1..3 the median per axis is (0.9, 0.1), whatever one outlier says.
  const FeatureIndex index({feature(1, {100, 100}, {0.9, 0.1}), feature(2, {101, 100}, {1.0, 0.0}),
                            feature(3, {99, 100}, {0.2, 0.3})});
  const auto v = linked_velocity(tracks_[0], index, 2);
  ASSERT_TRUE(v.has_value());
  EXPECT_NEAR((*v)[0], 0.9, 1e-12);
  EXPECT_NEAR((*v)[1], 0.1, 1e-12);
  EXPECT_FALSE(linked_velocity(tracks_[0], index, 4).has_value());
}

TEST_F(FeatureAssignment, AStoppedFeatureSupportsOnlyAnEstablishedLink) {
  // The car halts: its features are still tracked but no longer moving.
  TrackedFeature halted = feature(1, {100, 100}, {0.01, 0.0});
  halted.moving = false;
  const FeatureIndex index({}, {halted}, 10);
  EXPECT_NE(index.find_linked(FeatureLink{1, {0, 0}, 10}), nullptr);  // linked while moving for 10 frames
  EXPECT_EQ(index.find_linked(FeatureLink{1, {0, 0}, 9}), nullptr);   // a brief link: no support
  EXPECT_EQ(index.find(1), nullptr);                                   // and never a candidate for new links
  EXPECT_TRUE(index.inside(OrientedBox{100, 100, 5, 15, 0}).empty());
  const FeatureIndex disabled({}, {halted}, 0);
  EXPECT_EQ(disabled.find_linked(FeatureLink{1, {0, 0}, 100}), nullptr);
}

TEST(SplitMerge, MergedRegionIsReplacedByFeatureReconstructions) {
  // Two tracks side by side, one region covering both: each track's centre comes from its features.
  std::vector<TrackRecord> tracks(2);
  const std::vector<OrientedBox> predicted = {{100, 100, 5, 15, 0}, {104, 106, 5, 15, 0}};
  tracks[0].features = {FeatureLink{1, {0.2, 0.0}, 5}, FeatureLink{2, {-0.2, 0.0}, 5}};
  tracks[1].features = {FeatureLink{3, {0.2, 0.0}, 5}, FeatureLink{4, {-0.2, 0.0}, 5}};
  const FeatureIndex features({feature(1, {103.5, 100.5}, {2, 0}), feature(2, {97.5, 100.5}, {2, 0}),
                               feature(3, {107, 106}, {1, 0}), feature(4, {101, 106}, {1, 0})});
  const std::vector<OrientedBox> regions = {enclosing_box(predicted)};
  const RegionAssociation a = associate_regions(regions, predicted, 0.05);
  const SplitMergeResult r =
      resolve_split_merge(a, regions, in_frame(tracks, predicted, velocities_of(tracks.size())),
                          features, TrackerOptions{}, limits());
  ASSERT_EQ(r.measurements[0].kind, MeasurementKind::Centre);
  ASSERT_EQ(r.measurements[1].kind, MeasurementKind::Centre);
  EXPECT_NEAR(r.measurements[0].centre.x, 100.5, 1e-9);
  EXPECT_NEAR(r.measurements[0].centre.y, 100.5, 1e-9);
  EXPECT_NEAR(r.measurements[1].centre.x, 104.0, 1e-9);
  EXPECT_TRUE(r.free_regions.empty());  // the merged region starts no new track
}

TEST(SplitMerge, SplitKeepsTheRegionTheFeaturesFollowAndFreesTheOther) {
  std::vector<TrackRecord> tracks(1);
  const std::vector<OrientedBox> predicted = {{100, 100, 6, 30, 0}};
  tracks[0].features = {FeatureLink{1, {-0.3, 0.0}, 5}, FeatureLink{2, {-0.25, 0.1}, 5}};
  // Two regions moving differently: the rear one carries the track's features.
  const FeatureIndex features({feature(1, {91, 100}, {2, 0}), feature(2, {92.5, 100.6}, {2, 0}),
                               feature(3, {108, 100}, {3.5, 0})});
  const std::vector<OrientedBox> regions = {{92, 100, 5, 14, 0}, {108, 100, 5, 14, 0}};
  const RegionAssociation a = associate_regions(regions, predicted, 0.05);
  const SplitMergeResult r =
      resolve_split_merge(a, regions, in_frame(tracks, predicted, velocities_of(tracks.size())),
                          features, TrackerOptions{}, limits());
  ASSERT_EQ(r.measurements[0].kind, MeasurementKind::Box);
  EXPECT_EQ(r.measurements[0].box, regions[0]);
  EXPECT_EQ(r.free_regions, (std::vector<int>{1}));
}

TEST(SplitMerge, FragmentsNeverMakeABoxLargerThanTheLargestObject) {
  // A box that already took in a neighbour in a queue (12 px wide) sees the car beside it as one more
  // fragment with the same motion: its union would fit the enlarged prediction but is wider than any
  // vehicle, so that region is left over instead of growing the box further.
  std::vector<TrackRecord> tracks(1);
  const std::vector<OrientedBox> predicted = {{100, 100, 12, 20, 0}};
  const FeatureIndex features({feature(1, {100, 97}, {1, 0}), feature(2, {100, 106}, {1, 0})});
  const std::vector<OrientedBox> regions = {{100, 97, 6, 14, 0}, {100, 106, 5, 13, 0}};
  const RegionAssociation a = associate_regions(regions, predicted, 0.05);
  const SplitMergeResult unbounded =
      resolve_split_merge(a, regions, in_frame(tracks, predicted, velocities_of(1)),
                          features, TrackerOptions{}, limits());
  ASSERT_EQ(unbounded.measurements[0].kind, MeasurementKind::Box);
  EXPECT_GT(unbounded.measurements[0].box.width, 13.0);  // the two merged: 14.5 px wide
  const SplitMergeResult bounded =
      resolve_split_merge(a, regions, in_frame(tracks, predicted, velocities_of(1)),
                          features, TrackerOptions{}, limits({}, cv::Size2d(11.4, 38.6)));
  ASSERT_EQ(bounded.measurements[0].kind, MeasurementKind::Box);
  EXPECT_LT(bounded.measurements[0].box.width, 6.5);
  EXPECT_EQ(bounded.free_regions.size(), 1u);
}

TEST(SplitMerge, ARegionWiderThanAnyVehicleIsCutToTheTracksLane) {
  // `paper` seed 103: a truck's track (7 x 25 px along x) sees one blob over the truck and an untracked
  // car beside it, 15 px wide. Taken whole it grows the track over both (one box on two vehicles).
  std::vector<TrackRecord> tracks(1);
  const std::vector<OrientedBox> predicted = {{100, 100, 7, 25, 0}};
  const FeatureIndex none({});
  const std::vector<OrientedBox> regions = {{101, 104, 15, 26, 0}};  // the car on the track's +y side
  const RegionAssociation a = associate_regions(regions, predicted, 0.05);
  const SplitMergeResult open =
      resolve_split_merge(a, regions, in_frame(tracks, predicted, velocities_of(1)), none, TrackerOptions{}, limits());
  EXPECT_EQ(open.measurements[0].box, regions[0]);
  const SplitMergeResult r = resolve_split_merge(a, regions, in_frame(tracks, predicted, velocities_of(1)), none,
                                                 TrackerOptions{}, limits({}, {}, 11.4));
  ASSERT_EQ(r.measurements[0].kind, MeasurementKind::Box);
  const OrientedBox& box = r.measurements[0].box;
  EXPECT_NEAR(box.width, 7.0, 1e-9);   // the blob spans y 96.5-111.5; the lane 96.5-103.5
  EXPECT_NEAR(box.cy, 100.0, 1e-9);
  EXPECT_NEAR(box.cx, 101.0, 1e-9);    // along the lane, where the blob is
  EXPECT_NEAR(box.length, 26.0, 1e-9);
  EXPECT_TRUE(r.free_regions.empty());
  // A truck's own blob, one vehicle wide, is its box as it is.
  const std::vector<OrientedBox> own = {{100, 100, 8, 26, 0}};
  const SplitMergeResult kept = resolve_split_merge(associate_regions(own, predicted, 0.05), own,
                                                    in_frame(tracks, predicted, velocities_of(1)), none,
                                                    TrackerOptions{}, limits({}, {}, 11.4));
  EXPECT_EQ(kept.measurements[0].box, own[0]);
}

TEST(SplitMerge, ARegionAcrossTheTracksAxisIsWideToo) {
  // `paper` seed 108: a blob 10 x 20 px lying across a truck's track at 70 degrees to its axis (the
  // blob's shorter side is below the 11.4 px limit), over the truck and the one in the next lane.
  // Read along the track's axis, as the update reads it, it is about 20 px wide: cut to the lane.
  std::vector<TrackRecord> tracks(1);
  const std::vector<OrientedBox> predicted = {{100, 100, 8, 22, 0}};
  const FeatureIndex none({});
  const std::vector<OrientedBox> regions = {{101, 103, 10, 20, 70}};
  const RegionAssociation a = associate_regions(regions, predicted, 0.05);
  const SplitMergeResult r = resolve_split_merge(a, regions, in_frame(tracks, predicted, velocities_of(1)), none,
                                                 TrackerOptions{}, limits({}, {}, 11.4));
  ASSERT_EQ(r.measurements[0].kind, MeasurementKind::Box);
  EXPECT_LE(r.measurements[0].box.width, 8.0 + 1e-9) << "no wider than the track's lane";
  EXPECT_NEAR(r.measurements[0].box.angle_deg, 0.0, 1e-9);
  // The same blob along the axis is one vehicle wide and stays as it is.
  const std::vector<OrientedBox> along = {{101, 101, 10, 20, 0}};
  const SplitMergeResult kept = resolve_split_merge(associate_regions(along, predicted, 0.05), along,
                                                    in_frame(tracks, predicted, velocities_of(1)), none,
                                                    TrackerOptions{}, limits({}, {}, 11.4));
  EXPECT_EQ(kept.measurements[0].box, along[0]);
}

TEST(SplitMerge, FragmentsWithTheSameMotionAreOneMeasurement) {
  std::vector<TrackRecord> tracks(1);
  const std::vector<OrientedBox> predicted = {{100, 100, 5, 15, 0}};
  const FeatureIndex features({feature(1, {96, 100}, {2, 0}), feature(2, {104, 100}, {2.05, 0})});
  const std::vector<OrientedBox> regions = {{96.5, 100, 5, 7, 0}, {103.5, 100, 5, 7, 0}};
  const RegionAssociation a = associate_regions(regions, predicted, 0.05);
  const SplitMergeResult r =
      resolve_split_merge(a, regions, in_frame(tracks, predicted, velocities_of(tracks.size())),
                          features, TrackerOptions{}, limits());
  ASSERT_EQ(r.measurements[0].kind, MeasurementKind::Box);
  EXPECT_NEAR(r.measurements[0].box.cx, 100.0, 1e-3);
  EXPECT_NEAR(r.measurements[0].box.length, 14.0, 1e-3);
  EXPECT_TRUE(r.free_regions.empty());
}

}  // namespace
}  // namespace uavmot::tracking

namespace uavmot::tracking {
namespace {

TEST(SplitMerge, OneObjectTrackedInPiecesIsAbsorbedIntoTheSeniorTrack) {
  std::vector<TrackRecord> tracks(2);
  tracks[0].id = 1;
  tracks[0].hits = 4;
  tracks[1].id = 2;
  tracks[1].hits = 4;
  tracks[0].state = tracks[1].state = TrackState::Confirmed;
  const std::vector<OrientedBox> predicted = {{96, 100, 5, 7, 0}, {104, 100, 5, 7, 0}};  // two halves
  const std::vector<OrientedBox> regions = {{100, 100, 5, 15, 0}};                      // the whole car
  const FeatureIndex none({});
  const RegionAssociation a = associate_regions(regions, predicted, 0.05);
  const SplitMergeResult r =
      resolve_split_merge(a, regions, in_frame(tracks, predicted, velocities_of(2)),
                          none, TrackerOptions{}, limits(cv::Size2d(8.0, 20.0)));
  ASSERT_EQ(r.measurements[0].kind, MeasurementKind::Box);
  EXPECT_TRUE(r.absorbed[1]);
  EXPECT_FALSE(r.absorbed[0]);
  // The same region shared by two cars moving differently is a merge, nobody is absorbed.
  std::vector<cv::Vec2d> different = {cv::Vec2d(2, 0), cv::Vec2d(0.5, 0)};
  const SplitMergeResult m =
      resolve_split_merge(a, regions, in_frame(tracks, predicted, different),
                          none, TrackerOptions{}, limits(cv::Size2d(8.0, 20.0)));
  EXPECT_FALSE(m.absorbed[0] || m.absorbed[1]);
  // A region larger than one object (two cars side by side) is a merge too.
  const std::vector<OrientedBox> wide = {{100, 100, 11, 15, 0}};
  const RegionAssociation aw = associate_regions(wide, predicted, 0.05);
  const SplitMergeResult w =
      resolve_split_merge(aw, wide, in_frame(tracks, predicted, velocities_of(2)),
                          none, TrackerOptions{}, limits(cv::Size2d(8.0, 20.0)));
  EXPECT_FALSE(w.absorbed[0] || w.absorbed[1]);
}

TEST(SplitMerge, TwoCarsSideBySideAreNotPiecesOfOne) {
  // Two confirmed cars in adjacent lanes at one speed both claim a small blob between them.
  std::vector<TrackRecord> tracks(2);
  tracks[0].id = 1;
  tracks[1].id = 2;
  tracks[0].hits = tracks[1].hits = 20;
  tracks[0].state = tracks[1].state = TrackState::Confirmed;
  const std::vector<OrientedBox> predicted = {{100, 100, 6, 14, 0}, {100, 108, 6, 14, 0}};
  const std::vector<OrientedBox> regions = {{100, 104, 5, 6, 0}};
  const RegionAssociation a = associate_regions(regions, predicted, 0.05);
  ASSERT_EQ(a.tracks_of_region[0].size(), 2u);
  const cv::Size2d one_car(8.0, 20.0), largest_vehicle(11.0, 40.0);
  const FeatureIndex none({});
  const SplitMergeResult r =
      resolve_split_merge(a, regions, in_frame(tracks, predicted, velocities_of(2)),
                          none, TrackerOptions{}, limits(one_car, largest_vehicle));
  EXPECT_FALSE(r.absorbed[0] || r.absorbed[1]);
  // Without a bound on the largest vehicle, the two would be taken for pieces of one.
  const SplitMergeResult unbounded =
      resolve_split_merge(a, regions, in_frame(tracks, predicted, velocities_of(2)),
                          none, TrackerOptions{}, limits(one_car));
  EXPECT_TRUE(unbounded.absorbed[1]);
}

TEST(SplitMerge, TentativeTrackDoesNotTurnARegionIntoAMerge) {
  std::vector<TrackRecord> tracks(2);
  tracks[0].state = TrackState::Confirmed;
  tracks[1].state = TrackState::Tentative;
  const std::vector<OrientedBox> predicted = {{100, 100, 5, 15, 0}, {106, 101, 5, 15, 0}};
  const std::vector<OrientedBox> regions = {{101, 100, 5, 15, 0}};
  const FeatureIndex none({});
  const RegionAssociation a = associate_regions(regions, predicted, 0.05);
  ASSERT_EQ(a.tracks_of_region[0].size(), 2u);
  const SplitMergeResult r =
      resolve_split_merge(a, regions, in_frame(tracks, predicted, velocities_of(tracks.size())),
                          none, TrackerOptions{}, limits());
  ASSERT_EQ(r.measurements[0].kind, MeasurementKind::Box);
  EXPECT_EQ(r.measurements[0].box, regions[0]);
  EXPECT_EQ(r.measurements[1].kind, MeasurementKind::None);
}

}  // namespace
}  // namespace uavmot::tracking
