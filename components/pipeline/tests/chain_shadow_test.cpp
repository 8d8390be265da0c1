// The chain's account of the shadow correction (the line `uavmot process` logs): on a rendered
// `paper` scene its vehicles' shadows are found and taken out of the boxes, the way the sun casts
// them; on the same scene rendered without shadows nothing is moved. Taken out of the boxes' sizes
// too (`shadow_size_correction_factor`), the gradient regions come closer to the vehicles' size.

#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "uavmot/pipeline/chain.hpp"
#include "uavmot/sim/simulator.hpp"

namespace uavmot::pipeline {
namespace {

struct ShadowRun {
  ShadowSummary shadows;
  // Over the gradient regions whose centre lies on a moving vehicle: region minus vehicle, px.
  double median_width_excess = 0.0;
  double median_length_excess = 0.0;
};

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

ShadowRun run(double shadow_strength, int frames, double size_correction) {
  sim::Scenario scenario = sim::preset_scenario("paper");
  scenario.traffic.shadow_strength = shadow_strength;
  scenario.frames = frames;
  sim::Simulator simulator(scenario, 100);
  ChainOptions options;
  options.scene = simulator.scene();
  options.segmentation.regions.shadow_size_correction_factor = size_correction;
  Chain chain(options);
  sim::SimFrame rendered;
  std::vector<double> width_excess, length_excess;
  while (simulator.next(rendered)) {
    Frame frame;
    frame.stream_id = "paper";
    frame.index = rendered.index;
    frame.image = rendered.image;
    const ChainOutput out = chain.process(frame);
    for (const auto& region : out.segmentation.regions) {
      if (region.method == SegmentationMethod::Clustering) continue;  // made from features, left as they are
      for (const auto& object : rendered.objects) {
        if (!object.moving || !BoxFrame(object.box).contains({region.box.cx, region.box.cy})) continue;
        width_excess.push_back(region.box.width - object.box.width);
        length_excess.push_back(region.box.length - object.box.length);
        break;
      }
    }
  }
  EXPECT_EQ(chain.stage_times().frames, frames);
  EXPECT_GT(width_excess.size(), 200u);
  return {chain.shadow_summary(), median(width_excess), median(length_excess)};
}

TEST(ChainShadow, TheSunsShadowsAreTakenOutAndNoneWhereThereAreNone) {
  // `paper` casts 0.8 m shadows (2.3 px) toward +x, +y of the image: the boxes sat +1.1 / +0.8 px off.
  const ShadowRun sunny = run(0.45, 40, 1.0);
  EXPECT_GE(sunny.shadows.frames, 20);
  EXPECT_GT(sunny.shadows.median_px[0], 0.5);
  EXPECT_GT(sunny.shadows.median_px[1], 0.5);
  EXPECT_LT(std::hypot(sunny.shadows.median_px[0], sunny.shadows.median_px[1]), 2.5);
  const ShadowRun overcast = run(0.0, 40, 1.0);
  EXPECT_EQ(overcast.shadows.frames, 0);
}

TEST(ChainShadow, RegionsShrinkToTheVehiclesOwnSize) {
  const ShadowRun kept = run(0.45, 40, 0.0);
  const ShadowRun shrunk = run(0.45, 40, 1.0);
  // The blob holds the shadow: wider and longer than the vehicle; shrunk by the learnt offset's
  // extent it comes closer, without going below the vehicle's size.
  EXPECT_GT(kept.median_width_excess + kept.median_length_excess, 1.5);
  EXPECT_LT(shrunk.median_width_excess + shrunk.median_length_excess,
            kept.median_width_excess + kept.median_length_excess - 0.8);
  EXPECT_GT(shrunk.median_width_excess, -0.5);
  EXPECT_GT(shrunk.median_length_excess, -0.5);
  std::printf("[ChainShadow] median region - vehicle, width / length: %.2f / %.2f px kept, %.2f / %.2f px shrunk\n",
              kept.median_width_excess, kept.median_length_excess, shrunk.median_width_excess, shrunk.median_length_excess);
}

}  // namespace
}  // namespace uavmot::pipeline
