// The chain's account of the shadow correction (the line `uavmot process` logs): on a rendered
// `paper` scene its vehicles' shadows are found and taken out of the boxes, the way the sun casts
// them; on the same scene rendered without shadows nothing is moved.

#include <gtest/gtest.h>

#include "uavmot/pipeline/chain.hpp"
#include "uavmot/sim/simulator.hpp"

namespace uavmot::pipeline {
namespace {

ShadowSummary run(double shadow_strength, int frames) {
  sim::Scenario scenario = sim::preset_scenario("paper");
  scenario.traffic.shadow_strength = shadow_strength;
  scenario.frames = frames;
  sim::Simulator simulator(scenario, 100);
  ChainOptions options;
  options.scene = simulator.scene();
  Chain chain(options);
  sim::SimFrame rendered;
  while (simulator.next(rendered)) {
    Frame frame;
    frame.stream_id = "paper";
    frame.index = rendered.index;
    frame.image = rendered.image;
    chain.process(frame);
  }
  EXPECT_EQ(chain.stage_times().frames, frames);
  return chain.shadow_summary();
}

TEST(ChainShadow, TheSunsShadowsAreTakenOutAndNoneWhereThereAreNone) {
  // `paper` casts 0.8 m shadows (2.3 px) toward +x, +y of the image: the boxes sat +1.1 / +0.8 px off.
  const ShadowSummary sunny = run(0.45, 40);
  EXPECT_GE(sunny.frames, 20);
  EXPECT_GT(sunny.median_px[0], 0.5);
  EXPECT_GT(sunny.median_px[1], 0.5);
  EXPECT_LT(std::hypot(sunny.median_px[0], sunny.median_px[1]), 2.5);
  const ShadowSummary overcast = run(0.0, 40);
  EXPECT_EQ(overcast.frames, 0);
}

}  // namespace
}  // namespace uavmot::pipeline
