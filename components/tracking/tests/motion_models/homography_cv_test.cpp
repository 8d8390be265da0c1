// The motion model registry and its default, "homography_cv" (the paper's model, predictor.hpp).
#include <gtest/gtest.h>

#include "motion_model.hpp"
#include "predictor.hpp"
#include "uavmot/core/error.hpp"

namespace uavmot::tracking {
namespace {

KalmanState moving_car() {
  KalmanState s;
  s.mean << 100, 50, 2, -1, 5, 15, 30;
  return s;
}

TEST(MotionModels, TheDefaultIsThePapersHomographyControlledModel) {
  const TrackerOptions options;
  EXPECT_EQ(options.motion_model, "homography_cv");
  EXPECT_EQ(motion_model_names().front(), "homography_cv");
  const Homography h(1.01, 0.02, 3.0, -0.01, 0.99, -2.0, 1e-5, 0.0, 1.0);
  const KalmanState by_name = make_motion_model(options)->predict(moving_car(), h);
  const KalmanState direct = predict(moving_car(), h, process_noise(options));
  EXPECT_EQ(by_name.mean, direct.mean);  // the same arithmetic, bit for bit
  EXPECT_EQ(by_name.covariance, direct.covariance);
}

TEST(MotionModels, AnUnknownNameIsRejected) {
  TrackerOptions options;
  options.motion_model = "magic";
  EXPECT_THROW(make_motion_model(options), InvalidArgument);
  EXPECT_THROW(validate(options), InvalidArgument);
}

}  // namespace
}  // namespace uavmot::tracking
