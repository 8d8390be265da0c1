// The shift check: static texture in a cluster's window against a car moving with the cluster.

#include "../src/shift_check.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include <opencv2/imgproc.hpp>

#include "synthetic.hpp"
#include "uavmot/core/error.hpp"
#include "uavmot/segmentation/segmenter.hpp"

namespace uavmot::segmentation {
namespace {

using testing::features_on;
using testing::textured_background;
using testing::translation;
using testing::two_frames;
using testing::TwoFrames;

TEST(ShiftCheck, AMovingCarMatchesShiftedAndTheGroundUnshifted) {
  for (const cv::Vec2d& velocity : {cv::Vec2d(1.0, 0.0), cv::Vec2d(0.0, -2.0), cv::Vec2d(0.4, 0.0)}) {
    SCOPED_TRACE(velocity);
    const TwoFrames f = two_frames(velocity);
    const ImageCrop current{cv::Rect(60, 50, 80, 60), f.current(cv::Rect(60, 50, 80, 60))};
    const std::vector<ImageCrop> previous{{cv::Rect(50, 40, 90, 70), f.previous(cv::Rect(50, 40, 90, 70))}};
    const Homography previous_from_current = translation(-3.0, -3.0);

    const auto on_car = compare_shifts(current, f.car, {velocity, 0.0, 0.3}, previous_from_current, previous);
    ASSERT_TRUE(on_car.has_value());
    EXPECT_GT(on_car->pixels, 30);
    EXPECT_LT(on_car->moving_error, 0.5 * on_car->static_error);

    OrientedBox ground = f.car;  // the same box on the ground beside the car
    ground.cy += 12.0;
    const auto on_ground = compare_shifts(current, ground, {velocity, 0.5, 0.3}, previous_from_current, previous);
    ASSERT_TRUE(on_ground.has_value());
    EXPECT_LT(on_ground->static_error, 1.0);  // bilinear resampling only
    EXPECT_GT(on_ground->moving_error, 2.0 * on_ground->static_error + 1.0);
  }
}

TEST(ShiftCheck, TheSearchAbsorbsAnErrorInTheFeaturesVelocity) {
  const cv::Vec2d velocity(1.0, 0.0), estimate(1.5, -0.5);  // the features' estimate, half a pixel off in x and y
  const TwoFrames f = two_frames(velocity);
  const ImageCrop current{cv::Rect(60, 50, 80, 60), f.current(cv::Rect(60, 50, 80, 60))};
  const std::vector<ImageCrop> previous{{cv::Rect(50, 40, 90, 70), f.previous(cv::Rect(50, 40, 90, 70))}};
  const auto exact = compare_shifts(current, f.car, {estimate, 0.0, 0.3}, translation(-3.0, -3.0), previous);
  const auto searched = compare_shifts(current, f.car, {estimate, 0.5, 0.3}, translation(-3.0, -3.0), previous);
  ASSERT_TRUE(exact && searched);
  EXPECT_LT(searched->moving_error, 0.5 * exact->moving_error);
  EXPECT_LT(searched->moving_error, 1.0);
  EXPECT_EQ(searched->static_error, exact->static_error);
}

TEST(ShiftCheck, NothingWithoutAFastEnoughShift) {
  const TwoFrames f = two_frames({0.0, 0.0});
  const ImageCrop current{cv::Rect(60, 50, 80, 60), f.current(cv::Rect(60, 50, 80, 60))};
  const std::vector<ImageCrop> previous{{cv::Rect(50, 40, 90, 70), f.previous(cv::Rect(50, 40, 90, 70))}};
  EXPECT_FALSE(compare_shifts(current, f.car, {{0.1, 0.0}, 0.0, 0.3}, translation(-3.0, -3.0), previous));
  // With the search, only the shifts of at least 0.3 px are tried: static texture still wins.
  const auto searched = compare_shifts(current, f.car, {{0.1, 0.0}, 0.5, 0.3}, translation(-3.0, -3.0), previous);
  ASSERT_TRUE(searched);
  EXPECT_GT(searched->moving_error, searched->static_error);
}

TEST(ShiftCheck, NothingWithoutThePreviousPixels) {
  const TwoFrames f = two_frames({1.0, 0.0});
  const ImageCrop current{cv::Rect(60, 50, 80, 60), f.current(cv::Rect(60, 50, 80, 60))};
  const Homography previous_from_current = translation(-3.0, -3.0);
  // The previous frame's window ends left of where the car was.
  EXPECT_FALSE(compare_shifts(current, f.car, {{1.0, 0.0}, 0.5, 0.3}, previous_from_current,
                              {{cv::Rect(0, 0, 80, 160), f.previous(cv::Rect(0, 0, 80, 160))}}));
  EXPECT_FALSE(compare_shifts(current, f.car, {{1.0, 0.0}, 0.5, 0.3}, previous_from_current, {}));
  OrientedBox outside = f.car;  // a box outside the current window
  outside.cx = 10.0;
  EXPECT_FALSE(compare_shifts(current, outside, {{1.0, 0.0}, 0.5, 0.3}, previous_from_current,
                              {{cv::Rect(0, 0, 200, 160), f.previous}}));
}

// The evidence step moves a region only onto something that moves more plainly than what it held.
TEST(ShiftCheck, TheCarMovesMorePlainlyThanTheGroundBesideIt) {
  const cv::Vec2d velocity(1.0, 0.0);
  const TwoFrames f = two_frames(velocity);
  const ImageCrop current{cv::Rect(60, 50, 80, 60), f.current(cv::Rect(60, 50, 80, 60))};
  const std::vector<ImageCrop> previous{{cv::Rect(50, 40, 90, 70), f.previous(cv::Rect(50, 40, 90, 70))}};
  const ShiftSearch search{velocity, 0.5, 0.3};
  OrientedBox half_off = f.body;  // half on the car, half on the ground beside it
  half_off.cy += 4.0;
  OrientedBox ground = f.body;
  ground.cy += 12.0;
  const Homography previous_from_current = translation(-3.0, -3.0);
  // The reference is the shift check's own result on the box the region had.
  const auto checked = [&](const OrientedBox& box) { return compare_shifts(current, box, search, previous_from_current, previous); };
  EXPECT_TRUE(moves_more_plainly(current, f.body, checked(half_off), search, previous_from_current, previous));
  EXPECT_TRUE(moves_more_plainly(current, half_off, checked(ground), search, previous_from_current, previous));
  EXPECT_FALSE(moves_more_plainly(current, ground, checked(f.body), search, previous_from_current, previous));
  OrientedBox outside = f.body;  // nothing to compare it by: never a better place
  outside.cx = 10.0;
  ASSERT_FALSE(checked(outside).has_value());
  EXPECT_FALSE(moves_more_plainly(current, outside, checked(ground), search, previous_from_current, previous));
  EXPECT_TRUE(moves_more_plainly(current, f.body, checked(outside), search, previous_from_current, previous));
}

// A car drives past a bright static bar (a lane marking); a feature beside the car, dragged
// along by it, joins the car's cluster and so its window holds the bar, which the gradients
// segment as a region of its own. With the previous frame, the shift check drops the bar.
struct MarkingScene {
  Frame frame;
  MotionEstimate motion;
};

MarkingScene marking_scene(int64_t index) {
  MarkingScene s;
  const int x = 80 + static_cast<int>(index);  // the car drives 1 px per frame to the right
  s.frame.stream_id = s.motion.stream_id = "test";
  s.frame.index = s.motion.frame_index = index;
  s.frame.image = textured_background(cv::Size(200, 160), 100.0, 6.0, 0.0, 3);
  s.frame.image(cv::Rect(95, 86, 18, 3)).setTo(cv::Scalar(200));  // the marking, static
  s.frame.image(cv::Rect(x, 74, 15, 6)).setTo(cv::Scalar(170));  // the car
  s.motion.quality.valid = true;
  const OrientedBox car{x + 7.0, 76.5, 6.0, 15.0, 0.0};
  s.motion.features = features_on(car, {1.0, 0.0}, 1);
  TrackedFeature dragged = s.motion.features.back();
  dragged.id = 100;
  dragged.position = {x + 10.0, 84.0};  // between the car and the marking
  s.motion.features.push_back(dragged);
  return s;
}

bool region_near(const SegmentationResult& r, cv::Point2d p, double radius) {
  for (const Region& region : r.regions) {
    if (std::hypot(region.box.cx - p.x, region.box.cy - p.y) < radius) return true;
  }
  return false;
}

TEST(ShiftCheck, TheSegmenterDropsAStaticMarkingBesideAMovingCar) {
  SceneInfo scene;
  scene.gsd_m = 0.3;
  scene.fps = 25.0;
  const cv::Point2d marking(103.5, 87.0);
  for (const double ratio : {0.0, 1.0}) {
    SCOPED_TRACE(ratio);
    SegmentationOptions options;
    options.regions.shift_check_ratio = ratio;
    Segmenter segmenter(options, scene);
    const MarkingScene first = marking_scene(6), second = marking_scene(7);
    const auto before = segmenter.process(first.frame, first.motion);  // no previous frame: not checked
    EXPECT_TRUE(region_near(before, marking, 4.0));
    const auto after = segmenter.process(second.frame, second.motion);
    EXPECT_TRUE(region_near(after, {94.0, 76.5}, 3.0)) << "the car";
    EXPECT_EQ(region_near(after, marking, 4.0), ratio == 0.0) << "the marking";
    EXPECT_EQ(segmenter.last_stats().static_regions, ratio == 0.0 ? 0u : 1u);

    // A gap in the frame indices: nothing to compare with, nothing dropped.
    const MarkingScene later = marking_scene(9);
    EXPECT_TRUE(region_near(segmenter.process(later.frame, later.motion), marking, 4.0));
  }
}

// A dark car whose window gives no blob (here: every blob needs more supporting features than the
// cluster has) and whose one moving feature sits at its front end. The box around the feature sits
// half a car ahead; the motion evidence puts it on the car, reported as the segmentation's region.
MarkingScene dark_car_scene(int64_t index) {
  MarkingScene s;
  const int x = 80 + static_cast<int>(index);  // 1 px per frame to the right
  s.frame.stream_id = s.motion.stream_id = "test";
  s.frame.index = s.motion.frame_index = index;
  s.frame.image = textured_background(cv::Size(200, 160), 100.0, 6.0, 0.0, 3);
  s.frame.image(cv::Rect(x, 74, 15, 6)).setTo(cv::Scalar(60));
  s.motion.quality.valid = true;
  TrackedFeature front = features_on(OrientedBox{x + 7.0, 76.5, 6.0, 15.0, 0.0}, {1.0, 0.0}, 1).front();
  front.position = {x + 13.0, 76.5};
  s.motion.features = {front};
  return s;
}

TEST(ShiftCheck, ABloblessClusterGetsABoxOnItsMotionEvidence) {
  SceneInfo scene;
  scene.gsd_m = 0.3;  // the car's 15 x 6 px
  scene.fps = 25.0;
  for (const double lengths : {0.0, 0.5}) {
    SCOPED_TRACE(lengths);
    SegmentationOptions options;
    options.regions.min_supporting_features = 2;
    options.regions.fallback_evidence_lengths = lengths;
    Segmenter segmenter(options, scene);
    const MarkingScene first = dark_car_scene(6), second = dark_car_scene(7);
    segmenter.process(first.frame, first.motion);
    const auto result = segmenter.process(second.frame, second.motion);
    ASSERT_EQ(result.regions.size(), 1u);
    const Region& region = result.regions.front();
    const cv::Point2d car(87.0 + 7.0, 76.5), feature(87.0 + 13.0, 76.5);
    if (lengths > 0.0) {
      EXPECT_EQ(region.method, SegmentationMethod::Fusion);
      EXPECT_NEAR(region.box.cx, car.x, 1.5) << "on the car";
      EXPECT_NEAR(region.box.cy, car.y, 1.0);
      EXPECT_EQ(segmenter.last_stats().evidence_fallbacks, 1u);
      EXPECT_EQ(segmenter.last_stats().fallback_regions, 0u);
    } else {
      EXPECT_EQ(region.method, SegmentationMethod::Clustering);
      EXPECT_NEAR(region.box.cx, feature.x, 0.01) << "around the feature";
      EXPECT_EQ(segmenter.last_stats().evidence_fallbacks, 0u);
      EXPECT_EQ(segmenter.last_stats().fallback_regions, 1u);
    }
  }
  // Static ground under the feature: no evidence, the box around the feature stays.
  Segmenter segmenter([] {
    SegmentationOptions o;
    o.regions.min_supporting_features = 2;
    return o;
  }(), scene);
  MarkingScene first = dark_car_scene(6), second = dark_car_scene(7);
  second.frame.image = first.frame.image.clone();  // nothing moved
  segmenter.process(first.frame, first.motion);
  const auto result = segmenter.process(second.frame, second.motion);
  ASSERT_EQ(result.regions.size(), 1u);
  EXPECT_EQ(result.regions.front().method, SegmentationMethod::Clustering);
}

// The state a new process restores (Segmenter::save_state): the marking scene's frame 7 segmented
// by a new segmenter with frame 6's saved state is frame 7 as the first segmenter gave it, the
// marking dropped; a new one without it keeps the marking.
TEST(SegmenterState, ARestoredSegmenterSegmentsTheNextFrameAsTheOneThatSavedIt) {
  SceneInfo scene;
  scene.gsd_m = 0.3;
  scene.fps = 25.0;
  const cv::Point2d marking(103.5, 87.0);
  const MarkingScene first = marking_scene(6), second = marking_scene(7);
  Segmenter saved(SegmentationOptions{}, scene);
  EXPECT_EQ(saved.last_frame_index(), -1);
  saved.process(first.frame, first.motion);
  const std::vector<uint8_t> bytes = saved.save_state();

  Segmenter restored(SegmentationOptions{}, scene);
  restored.restore_state(bytes);
  EXPECT_EQ(restored.last_frame_index(), 6);
  EXPECT_EQ(restored.save_state(), bytes);
  const auto expected = saved.process(second.frame, second.motion);
  const auto got = restored.process(second.frame, second.motion);
  EXPECT_FALSE(region_near(got, marking, 4.0)) << "the marking";
  EXPECT_EQ(restored.last_stats().static_regions, 1u);
  ASSERT_EQ(got.regions.size(), expected.regions.size());
  for (size_t i = 0; i < got.regions.size(); ++i) {
    EXPECT_EQ(got.regions[i].box.cx, expected.regions[i].box.cx);
    EXPECT_EQ(got.regions[i].box.cy, expected.regions[i].box.cy);
    EXPECT_EQ(got.regions[i].box.width, expected.regions[i].box.width);
    EXPECT_EQ(got.regions[i].box.length, expected.regions[i].box.length);
  }

  Segmenter fresh(SegmentationOptions{}, scene);
  EXPECT_TRUE(region_near(fresh.process(second.frame, second.motion), marking, 4.0)) << "no state: the marking stays";
}

TEST(SegmenterState, ForeignDamagedOrCutBytesAreRefusedAndChangeNothing) {
  SceneInfo scene;
  scene.gsd_m = 0.3;
  scene.fps = 25.0;
  Segmenter saved(SegmentationOptions{}, scene);
  const MarkingScene first = marking_scene(6);
  saved.process(first.frame, first.motion);
  const std::vector<uint8_t> good = saved.save_state();
  ASSERT_GT(good.size(), 100u) << "the windows' pixels are in the state";

  std::vector<uint8_t> flipped = good;
  flipped[flipped.size() / 2] ^= 0x40;
  std::vector<uint8_t> foreign = good;
  foreign[1] = 'X';
  const std::vector<uint8_t> cut(good.begin(), good.end() - 5);
  Segmenter target(SegmentationOptions{}, scene);
  for (const auto& [bytes, why] : {std::pair{std::vector<uint8_t>{}, std::string("no 'USEGSTAT'")},
                                   std::pair{foreign, std::string("no 'USEGSTAT'")},
                                   std::pair{flipped, std::string("checksum")},
                                   std::pair{cut, std::string("truncated")}}) {
    SCOPED_TRACE(why);
    try {
      target.restore_state(bytes);
      ADD_FAILURE() << "accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << e.what();
    }
    EXPECT_EQ(target.last_frame_index(), -1);
  }
}

TEST(ShiftCheck, OptionsAreValidated) {
  SegmentationOptions options;
  options.regions.shift_check_ratio = -1.0;
  EXPECT_THROW(validate(options), InvalidArgument);
  options.regions.shift_check_ratio = 1.0;
  options.regions.shift_check_min_speed_px = std::nan("");
  EXPECT_THROW(validate(options), InvalidArgument);
}

}  // namespace
}  // namespace uavmot::segmentation
