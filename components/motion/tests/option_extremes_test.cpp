// Every motion option at each end of the range the configuration accepts, one option at a time:
// the estimator runs a short sequence with moving and parked vehicles without crashing, and what it
// reports is finite. A valid configuration must never take the process down (session 23 found a
// segmentation fault in the parallax fit that only `min_moving_speed_px: 0.1` on one seed reached).
#include <cmath>
#include <functional>
#include <string>
#include <type_traits>
#include <vector>

#include <gtest/gtest.h>

#include "test_support.hpp"
#include "uavmot/core/error.hpp"

namespace uavmot::motion {
namespace {

struct Variant {
  std::string name;  // "key=value"
  std::function<void(MotionOptions&)> apply;
};

// One variant per end of each numeric range, per value of each flag and per choice, in the order
// of for_each_motion_option. The setters find the field again by key on a fresh MotionOptions.
std::vector<Variant> variants() {
  std::vector<Variant> out;
  MotionOptions probe;
  for_each_motion_option(probe, [&](const char* key, auto& field, const auto& limits) {
    using Field = std::decay_t<decltype(field)>;
    using Limits = std::decay_t<decltype(limits)>;
    const std::string k = key;
    auto setter = [k](auto value) {
      return [k, value](MotionOptions& o) {
        for_each_motion_option(o, [&](const char* other, auto& f, const auto&) {
          if constexpr (std::is_assignable_v<decltype(f), decltype(value)>) {
            if (k == other) f = value;
          }
        });
      };
    };
    if constexpr (std::is_same_v<Limits, Flag>) {
      out.push_back({k + "=true", setter(true)});
      out.push_back({k + "=false", setter(false)});
    } else if constexpr (std::is_same_v<Limits, Choices>) {
      for (const char* name : limits.names) out.push_back({k + "=" + name, setter(std::string(name))});
    } else {
      static_assert(std::is_same_v<Limits, Range<Field>>);
      out.push_back({k + "=" + std::to_string(limits.low), setter(limits.low)});
      out.push_back({k + "=" + std::to_string(limits.high), setter(limits.high)});
    }
  });
  return out;
}

bool finite(const Homography& h) {
  for (int i = 0; i < 9; ++i) {
    if (!std::isfinite(h.val[i])) return false;
  }
  return true;
}

TEST(OptionExtremes, EveryAcceptedValueRunsAndReportsFiniteResults) {
  testing::WarpedSequence sequence(test::camera(3.0, 0.05, {320, 240}));
  sequence.set_patches(testing::scatter_patches(sequence, 6, 6, 3, 0.3, 2.0, 5));
  std::vector<cv::Mat> frames;
  for (int k = 1; k <= 12; ++k) frames.push_back(sequence.frame(k));

  int ran = 0;
  for (const Variant& v : variants()) {
    MotionOptions o;
    v.apply(o);
    try {
      validate(o);  // some ends contradict a default (min_track_frames 200 > history_frames 10)
    } catch (const InputError&) {
      continue;
    }
    MotionEstimator estimator(o);
    bool rejected = false;
    for (int k = 1; k <= static_cast<int>(frames.size()) && !rejected; ++k) {
      MotionEstimate e;
      try {
        e = estimator.process(test::make_frame(frames[static_cast<size_t>(k - 1)], k));
      } catch (const InputError& error) {
        // A frame this configuration cannot use (border_px 256 on 320 x 240) is a clear error, not a crash.
        EXPECT_NE(std::string(error.what()).find("frame 1"), std::string::npos) << v.name << ": " << error.what();
        rejected = true;
        continue;
      }
      ASSERT_TRUE(finite(e.homography)) << v.name << ", frame " << k;
      for (const TrackedFeature& f : e.features) {
        ASSERT_TRUE(std::isfinite(f.position.x) && std::isfinite(f.position.y)) << v.name << ", frame " << k;
        ASSERT_TRUE(std::isfinite(f.velocity[0]) && std::isfinite(f.velocity[1])) << v.name << ", frame " << k;
      }
    }
    ran += rejected ? 0 : 1;
  }
  // Nearly every end is usable alone; a list that stopped yielding variants would pass vacuously.
  EXPECT_GE(ran, 130);
}

}  // namespace
}  // namespace uavmot::motion
