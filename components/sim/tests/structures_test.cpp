// 3-D structures: parallax by the pinhole model, occlusion in the ground truth, the ground
// plane's homography, determinism, and flat presets rendering exactly as before.
#include <cmath>
#include <cstdio>
#include <map>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "../src/camera_path.hpp"
#include "test_scenarios.hpp"
#include "uavmot/core/error.hpp"
#include "uavmot/sim/simulator.hpp"

namespace uavmot::sim {
namespace {

std::vector<SimFrame> run(const Scenario& s, uint64_t seed, int frames) {
  Simulator sim(s, seed);
  std::vector<SimFrame> out;
  SimFrame frame;
  while (static_cast<int>(out.size()) < frames && sim.next(frame)) {
    out.push_back(frame);
    out.back().object_id_mask = frame.object_id_mask.clone();  // the simulator reuses the buffer
  }
  return out;
}

Scenario without_structures(Scenario s) {
  s.structures.building_density_per_ha = s.structures.tree_density_per_ha = s.structures.wall_density_per_ha = 0.0;
  return s;
}

cv::Point2d project(const cv::Matx34d& p, cv::Point3d x) {
  const cv::Vec3d h = p * cv::Vec4d(x.x, x.y, x.z, 1.0);
  return {h[0] / h[2], h[1] / h[2]};
}

// Image motion of a point at height h minus what the ground homography predicts for it.
cv::Point2d parallax(const detail::CameraPath& camera, cv::Point2d ground, double height, double t0, double t1) {
  const cv::Point3d x(ground.x, ground.y, -height);
  const cv::Point2d before = project(camera.projection(t0), x), after = project(camera.projection(t1), x);
  const cv::Matx33d h = camera.image_from_world(t1) * camera.image_from_world(t0).inv();
  return after - apply_homography(h, before);
}

TEST(Structures, ProjectionAgreesWithTheGroundHomographyOnTheGround) {
  for (const std::string preset : {"urban3d", "oblique"}) {
    const detail::CameraPath camera(preset_scenario(preset).camera, 3);
    for (double t : {0.0, 1.7, 6.1}) {
      const cv::Matx33d g = camera.image_from_world(t);
      for (const cv::Point2d w : {cv::Point2d(0, 0), cv::Point2d(40, -25), cv::Point2d(-80, 60)}) {
        const cv::Point2d a = project(camera.projection(t), {w.x, w.y, 0.0}), b = apply_homography(g, w);
        EXPECT_NEAR(a.x, b.x, 1e-9) << preset;
        EXPECT_NEAR(a.y, b.y, 1e-9) << preset;
      }
    }
  }
}

TEST(Structures, RoofPointsShowThePinholeParallax) {
  // Nadir, no wobble: a point at height h moves f v dt / (H - h) px per frame, the ground under
  // it f v dt / H, so the residual against the ground homography is v dt h / (gsd (H - h)).
  Scenario s = preset_scenario("urban3d");
  s.camera.tilt_deg = 0.0;
  s.camera.yaw_rate_dps = 0.0;
  s.camera.yaw_wobble_deg = 0.0;
  const detail::CameraPath camera(s.camera, 1);
  const double dt = 1.0 / s.fps, step = s.camera.speed_mps * dt, altitude = s.camera.altitude_m;
  for (double h : {5.0, 10.0, 20.0, 30.0}) {
    const double expected = step * h / (s.camera.gsd_m * (altitude - h));
    for (const cv::Point2d w : {cv::Point2d(10, 5), cv::Point2d(-60, 40), cv::Point2d(90, -70)}) {
      EXPECT_NEAR(cv::norm(parallax(camera, w, h, 2.0, 2.0 + dt)), expected, 1e-6 * expected + 1e-9) << h;
      EXPECT_NEAR(cv::norm(parallax(camera, w, 0.0, 2.0, 2.0 + dt)), 0.0, 1e-9);  // the ground has none
    }
  }
  // The presets as they fly (tilt and yaw wobble included), at the image centre.
  for (const std::string preset : {"urban3d", "oblique"}) {
    const Scenario p = preset_scenario(preset);
    const detail::CameraPath cam(p.camera, 1);
    const cv::Point2d centre = apply_homography(cam.image_from_world(2.0).inv(), {(p.camera.width - 1) / 2.0, (p.camera.height - 1) / 2.0});
    for (double h : {10.0, 20.0, 30.0}) {
      const double px = cv::norm(parallax(cam, centre, h, 2.0, 2.0 + 1.0 / p.fps));
      std::printf("[ parallax ] %s: roof at %2.0f m, image centre: %.3f px/frame against the ground homography\n", preset.c_str(), h, px);
      if (preset == "urban3d" && h >= 20.0) {
        EXPECT_GE(px, 0.27);
        EXPECT_LE(px, 1.0);
      }
      EXPECT_GT(px, 0.05);
    }
  }
}

TEST(Structures, ObliqueGsdGrowsTowardTheFarEdge) {
  const Scenario s = preset_scenario("oblique");
  const detail::CameraPath camera(s.camera, 1);
  const cv::Matx33d g = camera.image_from_world(0.0);
  const auto gsd_at = [&](double y) {
    const cv::Point2d a = apply_homography(g.inv(), {s.camera.width / 2.0, y}), b = apply_homography(g.inv(), {s.camera.width / 2.0, y + 1.0});
    return cv::norm(b - a);  // metres per pixel down the image
  };
  const double near = gsd_at(s.camera.height - 2.0), far = gsd_at(1.0);
  EXPECT_GT(far / near, 2.0) << "near " << near << " m/px, far " << far << " m/px";
  EXPECT_NO_THROW(Simulator(s, 1));  // the ground raster fits ground.raster_max_megapixels
}

TEST(Structures, OnlyVisibleVehiclePixelsAreInTheMaskAndVisibilityCountsThem) {
  // Vehicles, roads and ground do not depend on the structures, so the same scenario without
  // them shows what the structures hide.
  Scenario s = testing::clean_scenario("urban3d", 12);
  s.camera.width = 1024;
  s.camera.height = 768;
  const auto with = run(s, 2, 12), flat = run(without_structures(s), 2, 12);
  int partly_hidden = 0, under_tree = 0;
  for (size_t k = 0; k < with.size(); ++k) {
    const SimFrame& a = with[k];
    const SimFrame& b = flat[k];
    ASSERT_FALSE(a.structures.empty());
    EXPECT_TRUE(b.structures.empty());
    EXPECT_EQ(a.homography_from_previous, b.homography_from_previous);
    ASSERT_EQ(a.objects.size(), b.objects.size());
    std::map<int, int> seen, drawn;
    for (int y = 0; y < a.object_id_mask.rows; ++y)
      for (int x = 0; x < a.object_id_mask.cols; ++x) {
        const int ia = a.object_id_mask.at<int32_t>(y, x), ib = b.object_id_mask.at<int32_t>(y, x);
        if (ia != 0) {
          EXPECT_EQ(ia, ib);  // structures never add vehicle pixels
          ++seen[ia];
        }
        if (ib != 0) ++drawn[ib];
      }
    for (size_t i = 0; i < a.objects.size(); ++i) {
      const ObjectTruth& o = a.objects[i];
      ASSERT_EQ(o.id, b.objects[i].id);
      EXPECT_EQ(o.box, b.objects[i].box);
      if (drawn[o.id] == 0) continue;
      const double share = static_cast<double>(seen[o.id]) / drawn[o.id];
      EXPECT_NEAR(o.visibility, b.objects[i].visibility * share, 1e-12) << "frame " << k + 1 << " id " << o.id;
      if (share < 1.0) {
        ++partly_hidden;
        for (const StructureTruth& st : a.structures) {
          std::vector<cv::Point2f> poly;
          for (const auto& p : st.outline) poly.emplace_back(static_cast<float>(p.x), static_cast<float>(p.y));
          if (st.kind == StructureKind::Tree && cv::pointPolygonTest(poly, cv::Point2f(static_cast<float>(o.box.cx), static_cast<float>(o.box.cy)), true) > -2.0)
            ++under_tree;
        }
      }
    }
  }
  std::printf("[ occlusion ] %d partly or fully hidden vehicle instances in 12 frames, %d of them under a tree\n", partly_hidden, under_tree);
  EXPECT_GT(partly_hidden, 0);
  EXPECT_GT(under_tree, 0);
}

// Frame k-1 warped by the true H_k against frame k on the ground: away from vehicles (and their
// shadows) and from structures where they stand in either frame.
double ground_error(const SimFrame& prev, const SimFrame& cur) {
  const cv::Mat h(cur.homography_from_previous);
  cv::Mat warped, valid;
  cv::warpPerspective(prev.image, warped, h, cur.image.size(), cv::INTER_LINEAR);
  cv::warpPerspective(cv::Mat(prev.image.size(), CV_8U, cv::Scalar(255)), valid, h, cur.image.size(), cv::INTER_NEAREST);
  cv::Mat prev_vehicles = prev.object_id_mask != 0, warped_vehicles;
  cv::warpPerspective(prev_vehicles, warped_vehicles, h, cur.image.size(), cv::INTER_NEAREST);
  cv::Mat excluded = warped_vehicles | (cur.object_id_mask != 0);
  const auto fill = [&](const std::vector<cv::Point2d>& outline, const cv::Matx33d& map) {
    std::vector<cv::Point> poly;
    for (const auto& p : outline) {
      const cv::Point2d q = apply_homography(map, p);
      poly.emplace_back(static_cast<int>(std::lround(q.x)), static_cast<int>(std::lround(q.y)));
    }
    cv::fillConvexPoly(excluded, poly, cv::Scalar(255));
  };
  for (const StructureTruth& st : cur.structures) fill(st.outline, cv::Matx33d::eye());
  for (const StructureTruth& st : prev.structures) fill(st.outline, cur.homography_from_previous);
  cv::dilate(excluded, excluded, cv::Mat(), cv::Point(-1, -1), 4);
  cv::erode(valid, valid, cv::Mat(), cv::Point(-1, -1), 2);
  const cv::Mat use = valid & ~excluded;
  cv::Mat diff;
  cv::absdiff(warped, cur.image, diff);
  EXPECT_GT(cv::countNonZero(use), diff.total() / 4);
  return cv::mean(diff, use)[0];
}

TEST(Structures, GroundTruthHomographyIsTheGroundPlanes) {
  for (const std::string preset : {"urban3d", "oblique"}) {
    Scenario s = testing::clean_scenario(preset, 3);
    s.camera.width = 640;
    s.camera.height = 480;
    const auto frames = run(s, 4, 3);
    for (size_t k = 1; k < frames.size(); ++k) {
      EXPECT_FALSE(frames[k].structures.empty()) << preset;
      EXPECT_LT(ground_error(frames[k - 1], frames[k]), 1.5) << preset << " frame " << k + 1;
    }
  }
}

TEST(Structures, SameSeedSameBytes) {
  Scenario s = testing::small_scenario("urban3d", 3);
  s.camera.width = 640;
  s.camera.height = 480;
  const auto a = run(s, 9, 3), b = run(s, 9, 3);
  for (size_t k = 0; k < a.size(); ++k) {
    EXPECT_EQ(a[k].encoded_jpeg, b[k].encoded_jpeg);
    EXPECT_EQ(cv::countNonZero(a[k].object_id_mask != b[k].object_id_mask), 0);
    ASSERT_EQ(a[k].structures.size(), b[k].structures.size());
    for (size_t i = 0; i < a[k].structures.size(); ++i) {
      EXPECT_EQ(a[k].structures[i].id, b[k].structures[i].id);
      EXPECT_EQ(a[k].structures[i].outline, b[k].structures[i].outline);
    }
  }
}

uint64_t fnv1a(const std::vector<uint8_t>& bytes) {
  uint64_t h = 0xcbf29ce484222325ULL;
  for (uint8_t b : bytes) h = (h ^ b) * 0x100000001b3ULL;
  return h;
}

TEST(Structures, FlatPresetsRenderExactlyAsBefore) {
  // FNV-1a of the JPEG bytes of paper seed 1, frames 1-3, written before structures existed
  // (commit 3c764cc; libjpeg-turbo of Debian bookworm: another JPEG library gives other bytes).
  const uint64_t before[] = {0x145f12b273375de6ULL, 0x496c50576f08bce7ULL, 0xfe61b82f88168e88ULL};
  Simulator sim(preset_scenario("paper"), 1);
  SimFrame frame;
  for (int k = 0; k < 3; ++k) {
    ASSERT_TRUE(sim.next(frame));
    EXPECT_EQ(fnv1a(frame.encoded_jpeg), before[k]) << "frame " << k + 1;
    EXPECT_TRUE(frame.structures.empty());
  }
}

}  // namespace
}  // namespace uavmot::sim
