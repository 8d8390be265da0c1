#include "uavmot/segmentation/segmenter.hpp"

#include <gtest/gtest.h>

#include <limits>

#include <opencv2/imgproc.hpp>

#include "synthetic.hpp"
#include "uavmot/core/error.hpp"

namespace uavmot::segmentation {
namespace {

using testing::draw_car;
using testing::features_on;
using testing::textured_background;

SceneInfo test_scene() {
  SceneInfo s;
  s.gsd_m = 0.3;  // a 4.5 x 1.8 m car is 15 x 6 px
  s.fps = 25.0;
  return s;
}

// A car drawn as whole pixels and its continuous box.
struct Car {
  cv::Rect pixels;
  OrientedBox box() const {
    return {pixels.x + (pixels.width - 1) / 2.0, pixels.y + (pixels.height - 1) / 2.0,
            static_cast<double>(pixels.height), static_cast<double>(pixels.width), 0.0};
  }
};

struct Scene {
  Frame frame;
  MotionEstimate motion;
};

// Textured background with axis-aligned cars (value per car), all moving at `velocity`.
Scene make_scene(const std::vector<Car>& cars, const std::vector<int>& values, cv::Vec2d velocity) {
  Scene s;
  s.frame.stream_id = "test";
  s.frame.index = 7;
  s.frame.image = textured_background(cv::Size(200, 160), 100.0, 10.0, 2.0, 42);
  s.motion.stream_id = "test";
  s.motion.frame_index = 7;
  uint64_t id = 1;
  for (size_t i = 0; i < cars.size(); ++i) {
    s.frame.image(cars[i].pixels).setTo(cv::Scalar(values[i]));
    for (auto& f : features_on(cars[i].box(), velocity, id)) s.motion.features.push_back(f);
    id += 10;
  }
  return s;
}

SegmentationOptions with_method(SegmentationMethod method) {
  SegmentationOptions o;
  o.method = method;
  return o;
}

// Region whose centre is nearest to `truth`.
const Region* nearest(const std::vector<Region>& regions, const OrientedBox& truth) {
  const Region* best = nullptr;
  double best_d = 1e300;
  for (const auto& r : regions) {
    const double d = std::hypot(r.box.cx - truth.cx, r.box.cy - truth.cy);
    if (d < best_d) {
      best_d = d;
      best = &r;
    }
  }
  return best;
}

void expect_matches(const Region* r, const OrientedBox& truth, double position_tol, double size_tol,
                    double angle_tol_deg = 3.0) {
  ASSERT_NE(r, nullptr);
  EXPECT_NEAR(r->box.cx, truth.cx, position_tol);
  EXPECT_NEAR(r->box.cy, truth.cy, position_tol);
  EXPECT_NEAR(r->box.length, truth.length, size_tol);
  EXPECT_NEAR(r->box.width, truth.width, size_tol);
  EXPECT_NEAR(axis_angle_difference_deg(r->box.angle_deg, truth.angle_deg), 0.0, angle_tol_deg);
}

void expect_same(const SegmentationResult& a, const SegmentationResult& b) {
  ASSERT_EQ(a.clusters.size(), b.clusters.size());
  for (size_t i = 0; i < a.clusters.size(); ++i) {
    EXPECT_EQ(a.clusters[i].id, b.clusters[i].id);
    EXPECT_EQ(a.clusters[i].box, b.clusters[i].box);
    EXPECT_EQ(a.clusters[i].feature_ids, b.clusters[i].feature_ids);
  }
  ASSERT_EQ(a.regions.size(), b.regions.size());
  for (size_t i = 0; i < a.regions.size(); ++i) {
    EXPECT_EQ(a.regions[i].box, b.regions[i].box);
    EXPECT_EQ(a.regions[i].method, b.regions[i].method);
    EXPECT_EQ(a.regions[i].score, b.regions[i].score);
    EXPECT_EQ(a.regions[i].cluster_id, b.regions[i].cluster_id);
  }
}

// Two cars side by side, 4 px (1.2 m) apart, moving together: an overtaking manoeuvre.
const std::vector<Car> kPair = {{cv::Rect(93, 72, 15, 6)}, {cv::Rect(95, 82, 15, 6)}};

TEST(Segmenter, ClusteringUnderSegmentsAdjacentCarsMovingTogether) {
  const Scene s = make_scene(kPair, {175, 160}, {2.0, 0.0});
  Segmenter segmenter(with_method(SegmentationMethod::Clustering), test_scene());
  const auto result = segmenter.process(s.frame, s.motion);
  ASSERT_EQ(result.clusters.size(), 1u);
  EXPECT_EQ(result.clusters[0].feature_ids.size(), 10u);
  ASSERT_EQ(result.regions.size(), 1u);
  EXPECT_EQ(result.regions[0].method, SegmentationMethod::Clustering);
  EXPECT_EQ(result.regions[0].cluster_id, 1);
  EXPECT_EQ(result.frame_index, 7);
}

TEST(Segmenter, FusionSplitsTheUnderSegmentedClusterIntoBothCars) {
  const Scene s = make_scene(kPair, {175, 160}, {2.0, 0.0});
  Segmenter segmenter(SegmentationOptions{}, test_scene());
  const auto result = segmenter.process(s.frame, s.motion);
  ASSERT_EQ(result.clusters.size(), 1u);
  ASSERT_EQ(result.regions.size(), 2u);
  for (const Car& car : kPair) {
    const Region* r = nearest(result.regions, car.box());
    expect_matches(r, car.box(), 1.0, 1.5);
    EXPECT_EQ(r->method, SegmentationMethod::Fusion);
    EXPECT_EQ(r->cluster_id, 1);
  }
  EXPECT_EQ(segmenter.last_stats().fallback_regions, 0u);
}

TEST(Segmenter, EveryGradientAloneFindsASingleCar) {
  const std::vector<Car> car = {{cv::Rect(60, 50, 15, 6)}};
  const Scene s = make_scene(car, {170}, {0.0, -1.5});
  for (auto method : kSegmentationMethods) {  // a new method is held to this too
    if (method == SegmentationMethod::Clustering) continue;  // no image: the cluster's box
    SCOPED_TRACE(to_string(method));
    Segmenter segmenter(with_method(method), test_scene());
    const auto result = segmenter.process(s.frame, s.motion);
    ASSERT_EQ(result.regions.size(), 1u);
    EXPECT_EQ(result.regions[0].method, method);
    expect_matches(&result.regions[0], car[0].box(), 1.0, 2.0);
  }
}

TEST(Segmenter, RotatedCarGetsAnOrientedBox) {
  Scene s;
  s.frame.image = textured_background(cv::Size(200, 160), 100.0, 10.0, 2.0, 5);
  const OrientedBox truth{100.3, 80.6, 6.0, 15.0, 30.0};
  draw_car(s.frame.image, truth, 170);
  s.motion.features = features_on(truth, {1.5 * std::cos(CV_PI / 6), 1.5 * std::sin(CV_PI / 6)}, 1);
  Segmenter segmenter(SegmentationOptions{}, test_scene());
  const auto result = segmenter.process(s.frame, s.motion);
  ASSERT_EQ(result.regions.size(), 1u);
  expect_matches(&result.regions[0], truth, 1.0, 1.5, 3.0);
}

TEST(Segmenter, FusionSplitsCarsSideBySideAtAnObliqueAngle) {
  // Two cars at 40 degrees, 4 px apart across their heading: the pixel staircase makes the gap
  // thin along the image axes.
  Scene s;
  s.frame.image = textured_background(cv::Size(200, 160), 100.0, 10.0, 2.0, 11);
  const double a = 40.0 * CV_PI / 180.0, offset = 6.0 + 4.0;
  const OrientedBox first{100.0, 80.0, 6.0, 15.0, 40.0};
  const OrientedBox second{100.0 - std::sin(a) * offset, 80.0 + std::cos(a) * offset, 6.0, 15.0, 40.0};
  draw_car(s.frame.image, first, 175);
  draw_car(s.frame.image, second, 150);
  const cv::Vec2d velocity(1.5 * std::cos(a), 1.5 * std::sin(a));
  s.motion.features = features_on(first, velocity, 1);
  for (auto& f : features_on(second, velocity, 11)) s.motion.features.push_back(f);

  Segmenter clustering(with_method(SegmentationMethod::Clustering), test_scene());
  EXPECT_EQ(clustering.process(s.frame, s.motion).regions.size(), 1u);
  Segmenter fusion(SegmentationOptions{}, test_scene());
  const auto result = fusion.process(s.frame, s.motion);
  ASSERT_EQ(result.regions.size(), 2u);
  for (const auto& truth : {first, second}) expect_matches(nearest(result.regions, truth), truth, 1.0, 1.5, 4.0);
}

TEST(Segmenter, FeaturesOfAnInvisibleCarKeepABoxBesideTheSegmentedOne) {
  // The second car has the background's grey: no gradient, but its features still move.
  const Scene s = make_scene(kPair, {175, 100}, {2.0, 0.0});
  Segmenter segmenter(SegmentationOptions{}, test_scene());
  const auto result = segmenter.process(s.frame, s.motion);
  ASSERT_EQ(result.regions.size(), 2u);
  const Region* visible = nearest(result.regions, kPair[0].box());
  const Region* invisible = nearest(result.regions, kPair[1].box());
  ASSERT_NE(visible, invisible);
  EXPECT_EQ(visible->method, SegmentationMethod::Fusion);
  expect_matches(visible, kPair[0].box(), 1.0, 1.5);
  EXPECT_EQ(invisible->method, SegmentationMethod::Clustering);
  EXPECT_NEAR(invisible->box.cx, kPair[1].box().cx, 1.0);
  EXPECT_NEAR(invisible->box.cy, kPair[1].box().cy, 1.0);
  EXPECT_EQ(segmenter.last_stats().fallback_regions, 1u);

  SegmentationOptions no_fallback;
  no_fallback.regions.fallback_to_cluster_box = false;
  EXPECT_EQ(Segmenter(no_fallback, test_scene()).process(s.frame, s.motion).regions.size(), 1u);
}

// Moving features strung along 120 px of flat grey (on real FMV: corners along a shimmering roof
// edge) make one cluster, 8 car lengths long, and no blob: its box is no vehicle and is not
// returned. The same features along 24 px (1.6 lengths) still give the cluster's box.
TEST(Segmenter, AClusterBoxLongerThanAnyVehicleIsNoRegion) {
  for (const int span_px : {120, 24}) {
    Frame frame;
    frame.stream_id = "test";
    frame.index = 7;
    frame.image = cv::Mat(160, 200, CV_8UC1, cv::Scalar(100));
    MotionEstimate motion;
    motion.stream_id = "test";
    motion.frame_index = 7;
    uint64_t id = 1;
    for (int x = 40; x <= 40 + span_px; x += 6) {
      TrackedFeature f;
      f.id = id++;
      f.position = {static_cast<double>(x), 80.0};
      f.velocity = {1.5, 0.0};
      f.velocity_sigma = 0.05;
      f.age = 10;
      f.moving = true;
      motion.features.push_back(f);
    }
    Segmenter segmenter(SegmentationOptions{}, test_scene());
    const auto result = segmenter.process(frame, motion);
    ASSERT_EQ(result.clusters.size(), 1u) << span_px;
    if (span_px == 120) {
      EXPECT_TRUE(result.regions.empty()) << "a 120 px cluster box";
      EXPECT_EQ(segmenter.last_stats().fallback_regions, 0u);
    } else {
      ASSERT_EQ(result.regions.size(), 1u) << "a 24 px cluster box";
      EXPECT_EQ(result.regions[0].method, SegmentationMethod::Clustering);
    }
  }
}

TEST(Segmenter, CropPathGivesTheSameResultAsTheWholeFrame) {
  const Scene s = make_scene(kPair, {175, 160}, {2.0, 0.0});
  Segmenter segmenter(SegmentationOptions{}, test_scene());
  const auto whole = segmenter.process(s.frame, s.motion);

  const auto rois = segmenter.required_crops(s.motion, s.frame.image.size());
  ASSERT_EQ(rois.size(), 1u);
  EXPECT_LT(rois[0].area(), s.frame.image.size().area() / 4);  // only pixels near the cluster
  SegmentationInput input = make_segmentation_input(s.frame, rois);
  for (auto& crop : input.crops) crop.pixels = crop.pixels.clone();  // as if shipped elsewhere
  expect_same(whole, segmenter.process(input, s.motion));

  // A larger crop covering the window gives the same pixels, hence the same result.
  const cv::Rect big = cv::Rect(rois[0].x - 10, rois[0].y - 10, rois[0].width + 20, rois[0].height + 20);
  expect_same(whole, segmenter.process(make_segmentation_input(s.frame, {big}), s.motion));
}

TEST(Segmenter, ColourFramesAreSegmentedLikeTheirGrey) {
  const Scene s = make_scene(kPair, {175, 160}, {2.0, 0.0});
  Frame colour = s.frame;
  cv::cvtColor(s.frame.image, colour.image, cv::COLOR_GRAY2BGR);
  Segmenter segmenter(SegmentationOptions{}, test_scene());
  expect_same(segmenter.process(s.frame, s.motion), segmenter.process(colour, s.motion));
}

TEST(Segmenter, IsDeterministic) {
  const Scene s = make_scene(kPair, {175, 160}, {2.0, 0.0});
  Segmenter a(SegmentationOptions{}, test_scene());
  Segmenter b(SegmentationOptions{}, test_scene());
  const auto first = a.process(s.frame, s.motion);
  a.process(make_scene({{cv::Rect(10, 10, 15, 6)}}, {200}, {1.0, 1.0}).frame, s.motion);  // state must not leak
  expect_same(first, a.process(s.frame, s.motion));
  expect_same(first, b.process(s.frame, s.motion));
}

TEST(Segmenter, EmptyFrameFallsBackToClusterBoxes) {
  Scene s = make_scene(kPair, {175, 160}, {2.0, 0.0});
  s.frame.image = cv::Mat();
  Segmenter segmenter(SegmentationOptions{}, test_scene());
  const auto result = segmenter.process(s.frame, s.motion);
  ASSERT_EQ(result.clusters.size(), 1u);
  ASSERT_EQ(result.regions.size(), 1u);
  EXPECT_EQ(result.regions[0].method, SegmentationMethod::Clustering);
  EXPECT_EQ(segmenter.last_stats().windows_without_pixels, 1u);
}

TEST(Segmenter, BadFeaturesAreSkipped) {
  Scene s = make_scene({kPair[0]}, {175}, {2.0, 0.0});
  const Scene clean = s;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  TrackedFeature bad = s.motion.features.front();
  bad.id = 900;
  bad.position.x = nan;
  s.motion.features.push_back(bad);
  bad.id = 901;
  bad.position = {100, 80};
  bad.velocity[1] = std::numeric_limits<double>::infinity();
  s.motion.features.push_back(bad);
  bad.id = 902;
  bad.velocity = {2.0, 0.0};
  bad.position = {250, 80};  // right of the 200 px wide image
  s.motion.features.push_back(bad);
  bad.id = 903;
  bad.position = {-40, -40};
  s.motion.features.push_back(bad);

  Segmenter segmenter(SegmentationOptions{}, test_scene());
  const auto result = segmenter.process(s.frame, s.motion);
  EXPECT_EQ(segmenter.last_stats().clustering.skipped_non_finite, 2u);
  EXPECT_EQ(segmenter.last_stats().clustering.skipped_outside, 2u);
  expect_same(result, segmenter.process(clean.frame, clean.motion));
  ASSERT_EQ(result.regions.size(), 1u);
  expect_matches(&result.regions[0], kPair[0].box(), 1.0, 1.5);
}

TEST(Segmenter, UnusableCropsAreCountedAndSkipped) {
  const Scene s = make_scene({kPair[0]}, {175}, {2.0, 0.0});
  Segmenter segmenter(SegmentationOptions{}, test_scene());
  SegmentationInput input = make_segmentation_input(s.frame, segmenter.required_crops(s.motion, s.frame.image.size()));
  ASSERT_EQ(input.crops.size(), 1u);
  input.crops[0].pixels = cv::Mat(3, 3, CV_8U, cv::Scalar(0));  // size does not match the roi
  const auto result = segmenter.process(input, s.motion);
  EXPECT_EQ(segmenter.last_stats().invalid_crops, 1u);
  ASSERT_EQ(result.regions.size(), 1u);
  EXPECT_EQ(result.regions[0].method, SegmentationMethod::Clustering);
}

TEST(Segmenter, RejectsAnInvalidScene) {
  SceneInfo scene = test_scene();
  scene.gsd_m = 0.0;
  EXPECT_THROW(Segmenter(SegmentationOptions{}, scene), InvalidArgument);
}

}  // namespace
}  // namespace uavmot::segmentation
