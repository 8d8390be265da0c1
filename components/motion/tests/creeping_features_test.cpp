// Which slow features may use the creep floor: a queue's creeping car yes; a ground corner dragged
// by the car passing beside it, or a lone slow corner, no.
#include <gtest/gtest.h>

#include "creeping_features.hpp"

namespace uavmot::motion {
namespace {

CreepRule rule() {
  CreepRule r;
  r.creep_floor_px = 0.07;
  r.floor_px = 0.12;
  r.neighbour_radius_px = 13.0;  // one 4.5 m car at 0.35 m/px
  r.neighbour_ratio = 2.0;
  r.min_support = 2;
  return r;
}

struct Scene {
  std::vector<cv::Point2f> at;
  std::vector<cv::Vec2d> v;
  std::vector<unsigned char> decidable;
  size_t add(float x, float y, double vx, double vy, bool decided = true) {
    at.emplace_back(x, y);
    v.emplace_back(vx, vy);
    decidable.push_back(decided ? 1 : 0);
    return at.size() - 1;
  }
};

TEST(CreepingFeatures, AQueueOfSlowCarsCreeps) {
  Scene s;
  // Three cars nose to tail at 0.08-0.11 px/frame, two corners each, and still ground around.
  const size_t a = s.add(100, 100, 0.08, 0.0), b = s.add(104, 101, 0.085, 0.0);
  const size_t c = s.add(115, 100, 0.11, 0.0), d = s.add(119, 101, 0.10, 0.0);
  const size_t e = s.add(130, 100, 0.09, 0.0);
  const size_t ground = s.add(110, 110, 0.01, 0.0);
  const auto creeping = creeping_features(s.at, s.v, s.decidable, rule());
  for (const size_t k : {a, b, c, d, e}) EXPECT_TRUE(creeping[k]) << k;
  EXPECT_FALSE(creeping[ground]);  // below the creep floor
}

TEST(CreepingFeatures, AGroundCornerBesideAPassingCarIsVetoed) {
  Scene s;
  const size_t car = s.add(100, 100, 0.6, 0.0);
  s.add(106, 100, 0.6, 0.0);
  const size_t dragged = s.add(104, 106, 0.09, 0.01);  // a sixth of the car's velocity, its way
  s.add(98, 107, 0.08, 0.0);                           // and its neighbour, dragged alike
  const size_t far = s.add(100, 130, 0.09, 0.01);      // a creeping car two lengths away
  s.add(104, 131, 0.1, 0.0);
  const size_t facing = s.add(96, 92, -0.09, 0.0);     // a creeping car in the other lane
  s.add(90, 91, -0.1, 0.0);
  const auto creeping = creeping_features(s.at, s.v, s.decidable, rule());
  EXPECT_FALSE(creeping[car]);  // above the normal floor: no rule needed
  EXPECT_FALSE(creeping[dragged]);
  EXPECT_TRUE(creeping[far]);
  EXPECT_TRUE(creeping[facing]);
}

TEST(CreepingFeatures, ALoneSlowCornerOrOneWithoutAlikeNeighboursDoesNotCreep) {
  Scene s;
  const size_t lone = s.add(100, 100, 0.09, 0.0);
  const size_t crossing = s.add(200, 100, 0.09, 0.0);  // its neighbour goes across it
  s.add(205, 100, 0.0, 0.09);
  const size_t faster = s.add(300, 100, 0.07, 0.0);  // its neighbour creeps faster than the ratio allows
  s.add(305, 100, 0.11, 0.0);
  auto creeping = creeping_features(s.at, s.v, s.decidable, rule());
  EXPECT_FALSE(creeping[lone]);
  EXPECT_FALSE(creeping[crossing]);
  EXPECT_TRUE(creeping[faster]) << "0.11 is within twice 0.07";
  CreepRule strict = rule();
  strict.neighbour_ratio = 1.5;
  creeping = creeping_features(s.at, s.v, s.decidable, strict);
  EXPECT_FALSE(creeping[faster]);
  CreepRule alone = rule();
  alone.min_support = 1;
  creeping = creeping_features(s.at, s.v, s.decidable, alone);
  EXPECT_TRUE(creeping[lone]);
  EXPECT_TRUE(creeping[crossing]);
}

TEST(CreepingFeatures, OnlyDecidedFeaturesCountAndTheRuleCanBeOff) {
  Scene s;
  const size_t slow = s.add(100, 100, 0.09, 0.0);
  s.add(96, 100, 0.09, 0.0);
  s.add(104, 100, 0.6, 0.0, false);  // too young to be classified: no veto
  const size_t young = s.add(120, 100, 0.09, 0.0, false);
  s.add(124, 100, 0.09, 0.0);
  auto creeping = creeping_features(s.at, s.v, s.decidable, rule());
  EXPECT_TRUE(creeping[slow]);
  EXPECT_FALSE(creeping[young]);
  CreepRule off = rule();
  off.creep_floor_px = off.floor_px;  // creep_speed_factor 1, or a noise floor above the creep floor
  creeping = creeping_features(s.at, s.v, s.decidable, off);
  EXPECT_FALSE(creeping[slow]);
  CreepRule tiny = rule();
  tiny.neighbour_radius_px = 1e-9;  // creep_neighbour_lengths near 0: no neighbour, no support, no crash
  creeping = creeping_features(s.at, s.v, s.decidable, tiny);
  EXPECT_FALSE(creeping[slow]);
}

}  // namespace
}  // namespace uavmot::motion
