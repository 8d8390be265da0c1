#include "motion_model.hpp"

#include "uavmot/core/error.hpp"

namespace uavmot::tracking {

// Each model's factory, defined in its own file in motion_models/.
std::unique_ptr<MotionModel> make_homography_cv_model(const TrackerOptions& options);

namespace {

struct Entry {
  const char* name;
  MotionModelFactory make;
};

// Every motion model, by the name TrackerOptions::motion_model selects. The first is the default.
const std::vector<Entry>& models() {
  static const std::vector<Entry> list = {
      {"homography_cv", &make_homography_cv_model},
  };
  return list;
}

}  // namespace

std::vector<std::string> motion_model_names() {
  std::vector<std::string> names;
  for (const auto& m : models()) names.emplace_back(m.name);
  return names;
}

std::unique_ptr<MotionModel> make_motion_model(const TrackerOptions& options) {
  for (const auto& m : models()) {
    if (options.motion_model == m.name) return m.make(options);
  }
  throw InvalidArgument("tracking.motion_model: unknown value '" + options.motion_model + "'");
}

}  // namespace uavmot::tracking
