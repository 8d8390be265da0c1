#include "sim_tables.hpp"

#include <algorithm>
#include <cstdio>
#include <map>

#include <opencv2/imgproc.hpp>

#include "uavmot/eval/predictions.hpp"
#include "uavmot/eval/sim_recorder.hpp"
#include "uavmot/motion/motion_estimator.hpp"
#include "uavmot/segmentation/segmenter.hpp"
#include "uavmot/sim/scenario.hpp"
#include "uavmot/sim/simulator.hpp"

namespace uavmot::segmentation {

namespace {

// Moving features from the ground truth: corners on moving vehicles with their true velocity.
MotionEstimate truth_motion(const sim::SimFrame& rendered) {
  MotionEstimate estimate;
  estimate.frame_index = rendered.index;
  estimate.homography = rendered.homography_from_previous;
  estimate.quality.valid = true;
  std::vector<cv::Point2f> corners;
  cv::goodFeaturesToTrack(rendered.image, corners, 4000, 0.01, 3.0);
  std::map<int, int> per_object;
  for (const cv::Point2f& c : corners) {
    const int id = sim::object_at(rendered, cv::Point2d(c.x, c.y));
    const sim::ObjectTruth* object = id > 0 ? sim::find_object(rendered, id) : nullptr;
    if (object == nullptr || !object->moving) continue;
    TrackedFeature f;
    f.id = static_cast<uint64_t>(id) * 10000 + static_cast<uint64_t>(per_object[id]++);
    f.position = cv::Point2d(c.x, c.y);
    f.velocity = object->velocity_px;
    f.velocity_sigma = 0.05;
    f.age = 10;
    f.moving = true;
    estimate.features.push_back(f);
  }
  return estimate;
}

}  // namespace

SimTables run_sim_tables(const SimTablesRequest& request) {
  sim::Scenario scenario = sim::preset_scenario(request.preset);
  if (request.frames > 0) scenario.frames = request.frames;
  sim::Simulator simulator(scenario, request.seed);
  eval::SimRecorder truth(simulator);
  motion::MotionEstimator motion(motion::MotionOptions{}, simulator.scene());

  std::vector<Segmenter> segmenters;
  std::vector<eval::Predictions> predictions(request.methods.size());
  for (SegmentationMethod method : request.methods) {
    SegmentationOptions options = request.base;
    options.method = method;
    segmenters.emplace_back(options, simulator.scene());
  }

  SimTables tables;
  sim::SimFrame rendered;
  while (simulator.next(rendered)) {
    truth.add(rendered);
    Frame frame;
    frame.stream_id = request.preset;
    frame.index = rendered.index;
    frame.image = rendered.image;
    const MotionEstimate estimate = request.truth_features ? truth_motion(rendered) : motion.process(frame);
    for (const sim::ObjectTruth& object : rendered.objects) {
      if (!object.moving || object.visibility < 0.5) continue;
      ++tables.moving_instances;
      OrientedBox grown = object.box;
      grown.length += 2.0;
      grown.width += 2.0;
      const bool found = std::any_of(estimate.features.begin(), estimate.features.end(), [&](const TrackedFeature& f) {
        return f.moving && box_contains(grown, f.position);
      });
      tables.instances_with_moving_feature += found ? 1 : 0;
    }
    for (size_t i = 0; i < segmenters.size(); ++i) {
      const SegmentationResult result = segmenters[i].process(frame, estimate);
      std::vector<OrientedBox> boxes;
      for (const Region& region : result.regions) boxes.push_back(region.box);
      predictions[i].add_boxes(frame.index, boxes);
    }
  }

  tables.preset = request.preset;
  tables.seed = request.seed;
  tables.frames = scenario.frames;
  tables.truth_features = request.truth_features;
  tables.gsd_m = simulator.scene().gsd_m;
  for (size_t i = 0; i < request.methods.size(); ++i) {
    tables.results.emplace(request.methods[i], eval::evaluate(truth.sequence(), predictions[i]));
  }
  return tables;
}

std::string format_tables(const SimTables& tables) {
  std::string out;
  char line[512];
  std::snprintf(line, sizeof line, "Preset `%s`, seed %llu, %d frames, GSD %.2f m/px, moving features from %s.\n\n",
                tables.preset.c_str(), static_cast<unsigned long long>(tables.seed), tables.frames, tables.gsd_m,
                tables.truth_features ? "the ground truth (corners on moving vehicles)" : "the motion layer");
  out += line;
  std::snprintf(line, sizeof line,
                "Moving-object instances with a moving feature on them: %.1f %% of %lld.\n\n",
                tables.moving_instances > 0 ? 100.0 * static_cast<double>(tables.instances_with_moving_feature) /
                                                  static_cast<double>(tables.moving_instances)
                                            : 0.0,
                static_cast<long long>(tables.moving_instances));
  out += line;
  out += "Table I (completeness, % of moving-object instances)\n\n";
  out += "| method | correct | US | OS | miss | instances | false alarms / frame |\n|---|---|---|---|---|---|---|\n";
  for (const auto& [method, r] : tables.results) {
    const auto& c = r.completeness;
    std::snprintf(line, sizeof line, "| %s | %.1f | %.1f | %.1f | %.1f | %lld | %.2f |\n", to_string(method),
                  100.0 * c.correct_rate(), 100.0 * c.rate(c.under_segmented), 100.0 * c.rate(c.over_segmented),
                  100.0 * c.rate(c.missed), static_cast<long long>(c.instances), r.false_alarms.per_frame());
    out += line;
  }
  out += "\nTable II (precision, mean absolute error over correct instances, px (m))\n\n";
  out += "| method | e_x | e_y | e_w | e_l | samples |\n|---|---|---|---|---|---|\n";
  for (const auto& [method, r] : tables.results) {
    const auto& p = r.precision;
    std::snprintf(line, sizeof line, "| %s | %.2f (%.2f) | %.2f (%.2f) | %.2f (%.2f) | %.2f (%.2f) | %lld |\n",
                  to_string(method), p.error_x_px, p.error_x_m, p.error_y_px, p.error_y_m, p.error_width_px,
                  p.error_width_m, p.error_length_px, p.error_length_m, static_cast<long long>(p.samples));
    out += line;
  }
  return out;
}

}  // namespace uavmot::segmentation
