// "homography_cv", the paper's model (IV-D) and the default: constant velocity on the ground, the
// frame-to-frame homography as control input, random walk for size and angle (predictor.hpp).
#include "motion_model.hpp"
#include "predictor.hpp"

namespace uavmot::tracking {
namespace {

class HomographyConstantVelocity final : public MotionModel {
 public:
  explicit HomographyConstantVelocity(const TrackerOptions& options) : noise_(process_noise(options)) {}

  KalmanState predict(const KalmanState& posterior, const Homography& h) const override {
    return tracking::predict(posterior, h, noise_);
  }

 private:
  ProcessNoise noise_;
};

}  // namespace

std::unique_ptr<MotionModel> make_homography_cv_model(const TrackerOptions& options) {
  return std::make_unique<HomographyConstantVelocity>(options);
}

}  // namespace uavmot::tracking
