#include <algorithm>
#include <cmath>
#include <set>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "test_scenarios.hpp"
#include "uavmot/core/error.hpp"
#include "uavmot/sim/simulator.hpp"

namespace uavmot::sim {
namespace {

std::vector<SimFrame> run(const Scenario& s, uint64_t seed) {
  Simulator sim(s, seed);
  std::vector<SimFrame> frames;
  SimFrame frame;
  while (sim.next(frame)) frames.push_back(frame);
  return frames;
}

bool same_image(const cv::Mat& a, const cv::Mat& b) {
  return a.size() == b.size() && a.type() == b.type() && cv::countNonZero(a != b) == 0;
}

TEST(Simulator, SameSeedGivesIdenticalFramesAndTruth) {
  const Scenario s = testing::small_scenario("paper", 4);
  const auto a = run(s, 7), b = run(s, 7);
  ASSERT_EQ(a.size(), 4u);
  ASSERT_EQ(b.size(), 4u);
  for (size_t k = 0; k < a.size(); ++k) {
    EXPECT_EQ(a[k].encoded_jpeg, b[k].encoded_jpeg) << "frame " << k + 1;
    EXPECT_TRUE(same_image(a[k].object_id_mask, b[k].object_id_mask));
    ASSERT_EQ(a[k].objects.size(), b[k].objects.size());
    for (size_t i = 0; i < a[k].objects.size(); ++i) {
      EXPECT_EQ(a[k].objects[i].id, b[k].objects[i].id);
      EXPECT_EQ(a[k].objects[i].box, b[k].objects[i].box);
    }
    EXPECT_EQ(a[k].homography_from_previous, b[k].homography_from_previous);
  }
}

TEST(Simulator, DifferentSeedGivesDifferentFrames) {
  const Scenario s = testing::small_scenario("paper", 2);
  const auto a = run(s, 1), b = run(s, 2);
  EXPECT_NE(a[1].encoded_jpeg, b[1].encoded_jpeg);
}

TEST(Simulator, FramesAreNumberedFromOneWithIdentityFirst) {
  const auto frames = run(testing::small_scenario("paper", 3), 3);
  ASSERT_EQ(frames.size(), 3u);
  EXPECT_EQ(frames[0].index, 1);
  EXPECT_EQ(frames[2].index, 3);
  EXPECT_EQ(frames[0].homography_from_previous, Homography::eye());
  EXPECT_EQ(frames[1].image.type(), CV_8UC1);
  EXPECT_EQ(frames[1].image.cols, 320);
  EXPECT_EQ(frames[1].object_id_mask.type(), CV_32S);
  EXPECT_DOUBLE_EQ(frames[1].homography_from_previous(2, 2), 1.0);
}

// Mean absolute difference between frame k and frame k-1 warped by h, over background pixels
// (no vehicle or shadow nearby in either frame) inside the warped image.
double background_error(const SimFrame& previous, const SimFrame& current, const Homography& h) {
  cv::Mat warped, valid;
  cv::warpPerspective(previous.image, warped, cv::Mat(h), current.image.size(), cv::INTER_LINEAR);
  cv::warpPerspective(cv::Mat(previous.image.size(), CV_8U, cv::Scalar(255)), valid, cv::Mat(h), current.image.size(),
                      cv::INTER_NEAREST);
  cv::Mat prev_objects, warped_objects;
  cv::Mat(previous.object_id_mask != 0).copyTo(prev_objects);
  cv::warpPerspective(prev_objects, warped_objects, cv::Mat(h), current.image.size(), cv::INTER_NEAREST);
  cv::Mat objects = warped_objects | (current.object_id_mask != 0);
  cv::dilate(objects, objects, cv::Mat(), cv::Point(-1, -1), 4);  // vehicles plus their shadows
  cv::erode(valid, valid, cv::Mat(), cv::Point(-1, -1), 2);
  const cv::Mat use = valid & ~objects;
  cv::Mat diff;
  cv::absdiff(warped, current.image, diff);
  EXPECT_GT(cv::countNonZero(use), diff.total() / 2);
  return cv::mean(diff, use)[0];
}

TEST(Simulator, TrueHomographyAlignsTheBackground) {
  for (const std::string preset : {"paper", "fastcam"}) {
    const auto frames = run(testing::clean_scenario(preset, 4), 5);
    for (size_t k = 1; k < frames.size(); ++k) {
      const Homography h = frames[k].homography_from_previous;
      const double exact = background_error(frames[k - 1], frames[k], h);
      // Half a pixel of error in the homography must be clearly visible in the residual.
      const Homography shifted = cv::Matx33d(1, 0, 0.5, 0, 1, 0.5, 0, 0, 1) * h;
      const double off = background_error(frames[k - 1], frames[k], shifted);
      EXPECT_LT(exact, 1.5) << preset << " frame " << k + 1;
      EXPECT_LT(exact, 0.45 * off) << preset << " frame " << k + 1;
    }
  }
}

TEST(Simulator, FastcamMovesTensOfPixelsPerFrame) {
  const auto frames = run(testing::clean_scenario("fastcam", 3), 2);
  const cv::Point2d centre(159.5, 119.5);
  const cv::Point2d moved = apply_homography(frames[2].homography_from_previous, centre);
  EXPECT_GT(cv::norm(moved - centre), 10.0);
}

TEST(Simulator, ParkedVehiclesFollowTheBackgroundExactly) {
  const auto frames = run(testing::small_scenario("dense", 5), 11);
  int checked = 0;
  for (size_t k = 1; k < frames.size(); ++k) {
    for (const ObjectTruth& o : frames[k].objects) {
      if (!o.parked) continue;
      EXPECT_FALSE(o.moving);
      EXPECT_EQ(o.velocity_px, cv::Vec2d(0, 0));
      const ObjectTruth* before = find_object(frames[k - 1], o.id);
      if (before == nullptr) continue;
      const cv::Point2d predicted = apply_homography(frames[k].homography_from_previous, {before->box.cx, before->box.cy});
      EXPECT_NEAR(predicted.x, o.box.cx, 1e-6);
      EXPECT_NEAR(predicted.y, o.box.cy, 1e-6);
      ++checked;
    }
  }
  EXPECT_GT(checked, 0) << "the dense preset should show parked vehicles";
}

TEST(Simulator, MovingVehiclesMoveRelativeToTheBackgroundByTheirVelocity) {
  const auto frames = run(testing::small_scenario("paper", 4), 4);
  int checked = 0;
  for (size_t k = 1; k < frames.size(); ++k) {
    for (const ObjectTruth& o : frames[k].objects) {
      const ObjectTruth* before = find_object(frames[k - 1], o.id);
      if (!o.moving || before == nullptr) continue;
      const cv::Point2d predicted = apply_homography(frames[k].homography_from_previous, {before->box.cx, before->box.cy});
      const cv::Point2d relative(o.box.cx - predicted.x, o.box.cy - predicted.y);
      EXPECT_NEAR(relative.x, o.velocity_px[0], 0.05);
      EXPECT_NEAR(relative.y, o.velocity_px[1], 0.05);
      EXPECT_GT(cv::norm(relative), 0.01);
      ++checked;
    }
  }
  EXPECT_GT(checked, 3);
}

TEST(Simulator, VehiclesHaveTheirTrueSizeForTheGsd) {
  const auto frames = run(testing::small_scenario("paper", 1), 9);
  const double gsd = preset_scenario("paper").camera.gsd_m;
  int cars = 0;
  for (const ObjectTruth& o : frames[0].objects) {
    if (o.kind != VehicleKind::Car) continue;
    EXPECT_NEAR(o.box.length * gsd, 4.55, 0.45);
    EXPECT_NEAR(o.box.width * gsd, 1.8, 0.2);
    ++cars;
  }
  EXPECT_GT(cars, 3);
}

TEST(Simulator, SlowPresetMoversCrawlBelowAPixelPerFrame) {
  Scenario s = testing::small_scenario("slow", 2);
  const auto frames = run(s, 3);
  std::vector<double> speeds;
  for (const ObjectTruth& o : frames[1].objects)
    if (o.moving) speeds.push_back(cv::norm(o.velocity_px));
  ASSERT_GT(speeds.size(), 3u);
  EXPECT_LE(*std::max_element(speeds.begin(), speeds.end()), 0.65);
  std::sort(speeds.begin(), speeds.end());
  EXPECT_GE(speeds[speeds.size() / 2], 0.15);
}

TEST(Simulator, MaskAndObjectAtAgreeWithTheBoxes) {
  const auto frames = run(testing::small_scenario("paper", 1), 2);
  const SimFrame& f = frames[0];
  int checked = 0;
  for (const ObjectTruth& o : f.objects) {
    if (o.visibility < 1.0) continue;
    EXPECT_EQ(object_at(f, {o.box.cx, o.box.cy}), o.id);
    EXPECT_EQ(is_on_moving_object(f, {o.box.cx, o.box.cy}), o.moving);
    // Just outside the box along the length axis: nothing there without tolerance.
    const double a = o.box.angle_deg * CV_PI / 180.0;
    const cv::Point2d outside(o.box.cx + std::cos(a) * (o.box.length / 2 + 1.6), o.box.cy + std::sin(a) * (o.box.length / 2 + 1.6));
    if (object_at(f, outside) == 0) {
      EXPECT_EQ(object_at(f, outside, 2.5), o.id);
      ++checked;
    }
  }
  EXPECT_GT(checked, 2);
  EXPECT_EQ(object_at(f, {-50.0, -50.0}, 3.0), 0);
}

TEST(Simulator, MissingTextureFolderIsAnInputError) {
  Scenario s = testing::small_scenario("paper", 1);
  s.ground.texture_dir = "/nonexistent/texture";
  try {
    Simulator sim(s, 1);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/texture"), std::string::npos);
  }
}

TEST(Simulator, ProceduralGroundNeedsNoImages) {
  Scenario s = testing::small_scenario("paper", 2);
  s.ground.texture_dir = "procedural";
  const auto frames = run(s, 1);
  ASSERT_EQ(frames.size(), 2u);
  cv::Scalar mean, stddev;
  cv::meanStdDev(frames[1].image, mean, stddev);
  EXPECT_GT(stddev[0], 5.0);
}

}  // namespace
}  // namespace uavmot::sim

namespace uavmot::sim {
namespace {

TEST(Simulator, VehiclesNeverOverlapEvenAtJunctionsAndLaneChanges) {
  Scenario s = testing::small_scenario("dense", 40);
  s.camera.width = 640;
  s.camera.height = 480;
  const auto frames = run(s, 1);
  int pairs_close = 0;
  for (const SimFrame& f : frames) {
    for (size_t i = 0; i < f.objects.size(); ++i)
      for (size_t j = i + 1; j < f.objects.size(); ++j) {
        const double inter = intersection_area(f.objects[i].box, f.objects[j].box);
        EXPECT_LT(inter, 0.02 * box_area(f.objects[i].box))
            << "frame " << f.index << " ids " << f.objects[i].id << " and " << f.objects[j].id;
        if (std::hypot(f.objects[i].box.cx - f.objects[j].box.cx, f.objects[i].box.cy - f.objects[j].box.cy) < 15.0) ++pairs_close;
      }
  }
  EXPECT_GT(pairs_close, 20) << "dense traffic should bring vehicles close together";
}

TEST(Simulator, DenseTrafficHasManyMoversAndParkedVehicles) {
  Scenario s = testing::small_scenario("dense", 2);
  s.camera.width = 640;
  s.camera.height = 480;
  const auto frames = run(s, 2);
  int parked = 0, moving = 0;
  for (const ObjectTruth& o : frames[1].objects) {
    if (o.parked) ++parked;
    if (o.moving) ++moving;
    EXPECT_FALSE(o.parked && o.moving);
  }
  EXPECT_GT(moving, 10);
  EXPECT_GT(parked, 0);
}

}  // namespace
}  // namespace uavmot::sim

namespace uavmot::sim {
namespace {

TEST(Simulator, TooLargeAGroundAreaIsRefusedQuickly) {
  Scenario s = preset_scenario("fastcam");
  s.frames = 100000;
  try {
    Simulator sim(s, 1);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("raster_max_megapixels"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace uavmot::sim

namespace uavmot::sim {
namespace {

TEST(Simulator, VehiclesEnterAndLeaveTheView) {
  Scenario s = testing::small_scenario("paper", 60);
  const auto frames = run(s, 6);
  std::set<int> first, last, all;
  for (const ObjectTruth& o : frames.front().objects) first.insert(o.id);
  for (const ObjectTruth& o : frames.back().objects) last.insert(o.id);
  for (const SimFrame& f : frames)
    for (const ObjectTruth& o : f.objects) {
      all.insert(o.id);
      EXPECT_GT(o.visibility, 0.0);
      EXPECT_LE(o.visibility, 1.0);
    }
  int entered = 0, left = 0;
  for (int id : all) {
    if (!first.count(id)) ++entered;
    if (!last.count(id)) ++left;
  }
  EXPECT_GT(entered, 0);
  EXPECT_GT(left, 0);
  // Ids are given in order of first appearance, from 1.
  EXPECT_EQ(*all.begin(), 1);
  EXPECT_EQ(*all.rbegin(), static_cast<int>(all.size()));
}

}  // namespace
}  // namespace uavmot::sim

namespace uavmot::sim {
namespace {

Scenario scripted_only(const std::vector<ScriptedVehicle>& vehicles, int frames) {
  Scenario s = testing::clean_scenario("paper", frames);
  s.traffic.flow_per_lane_vph = 0.0;
  s.traffic.parked_vehicles = 0;
  s.scripted = vehicles;
  return s;
}

TEST(Simulator, ScriptedVehicleStartsAtTheImageCentreAndFollowsItsSpeedKeys) {
  ScriptedVehicle car;
  car.speed = {{0.0, 10.0}, {1.0, 10.0}, {1.5, 0.0}};
  const Scenario s = scripted_only({car}, 50);
  const auto frames = run(s, 3);
  ASSERT_EQ(frames.front().objects.size(), 1u);
  const ObjectTruth& first = frames.front().objects.front();
  // On the main road's outer lane, next to the centreline point nearest the image centre.
  const double lane_offset_px = 1.5 * s.roads.lane_width_m / s.camera.gsd_m;
  EXPECT_LT(std::hypot(first.box.cx - (s.camera.width - 1) / 2.0, first.box.cy - (s.camera.height - 1) / 2.0), lane_offset_px);
  for (const SimFrame& f : frames) {
    const double t = static_cast<double>(f.index - 1) / s.fps;
    const double expected = t <= 1.0 ? 10.0 : std::max(0.0, 10.0 - 20.0 * (t - 1.0));
    ASSERT_EQ(f.objects.size(), 1u) << "frame " << f.index;
    EXPECT_NEAR(f.objects.front().speed_mps, expected, 1e-9) << "frame " << f.index;
    EXPECT_EQ(f.objects.front().moving, expected >= s.traffic.moving_threshold_mps) << "frame " << f.index;
  }
  // Standing still after 1.5 s: the box stays on the same ground point.
  const ObjectTruth& a = frames[40].objects.front();
  const ObjectTruth& b = frames[49].objects.front();
  cv::Point2d carried(a.box.cx, a.box.cy);
  for (size_t k = 41; k <= 49; ++k) carried = apply_homography(frames[k].homography_from_previous, carried);
  EXPECT_NEAR(carried.x, b.box.cx, 1e-6);
  EXPECT_NEAR(carried.y, b.box.cy, 1e-6);
}

TEST(Simulator, ScriptedLaneChangeMovesTheVehicleOneLaneOver) {
  // Two cars at the same speed, 10 m apart in the outer lane; the one ahead moves one lane in.
  ScriptedVehicle stays, changes;
  stays.speed = changes.speed = {{0.0, 8.0}};
  changes.start_m = 10.0;
  changes.lane_changes = {{0.2, 1}};
  const Scenario s = scripted_only({stays, changes}, 110);  // 4.4 s: the change takes 3.5 s
  const auto frames = run(s, 5);
  ASSERT_EQ(frames.back().objects.size(), 2u);
  const ObjectTruth& a = frames.back().objects[0];
  const ObjectTruth& b = frames.back().objects[1];
  const double heading = a.box.angle_deg * 3.14159265358979323846 / 180.0;
  const cv::Point2d d(b.box.cx - a.box.cx, b.box.cy - a.box.cy);
  const double along = std::abs(std::cos(heading) * d.x + std::sin(heading) * d.y);
  const double across = std::abs(-std::sin(heading) * d.x + std::cos(heading) * d.y);
  EXPECT_NEAR(along, 10.0 / s.camera.gsd_m, 1.0);
  EXPECT_NEAR(across, s.roads.lane_width_m / s.camera.gsd_m, 0.5);
}

TEST(Simulator, ScriptOnARoadTheNetworkLacksIsAnInputError) {
  ScriptedVehicle car;
  car.road = 9;
  try {
    run(scripted_only({car}, 2), 1);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("scripted[0].road 9"), std::string::npos) << e.what();
  }
  car.road = 0;
  car.start_m = 5000.0;
  EXPECT_THROW(run(scripted_only({car}, 2), 1), InputError);
  car.start_m = 0.0;
  car.lane_changes = {{1.0, 3}};  // the paper preset's main road has two lanes per direction
  try {
    run(scripted_only({car}, 2), 1);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("scripted[0].lane_changes[0].lane 3"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace uavmot::sim
