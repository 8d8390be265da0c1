#include "uavmot/eval/sim_recorder.hpp"

#include <opencv2/imgcodecs.hpp>

#include "uavmot/core/error.hpp"

namespace uavmot::eval {

SimRecorder::SimRecorder(const sim::Simulator& simulator, bool keep_masks)
    : keep_masks_(keep_masks), masks_(std::make_shared<std::map<int64_t, std::vector<uint8_t>>>()) {
  const sim::Scenario& s = simulator.scenario();
  sequence_.info.name = s.name;
  sequence_.info.length = s.frames;
  sequence_.info.width = s.camera.width;
  sequence_.info.height = s.camera.height;
  sequence_.info.fps = s.fps;
  sequence_.info.gsd_m = simulator.scene().gsd_m;
  const sim::StructureParams& st = s.structures;
  sequence_.has_structures = st.building_density_per_ha > 0.0 || st.tree_density_per_ha > 0.0 || st.wall_density_per_ha > 0.0;
  if (keep_masks_) {
    auto masks = masks_;
    sequence_.id_mask = [masks](int64_t frame) {
      auto it = masks->find(frame);
      if (it == masks->end()) return cv::Mat();
      return cv::imdecode(it->second, cv::IMREAD_UNCHANGED);
    };
  }
}

void SimRecorder::add(const sim::SimFrame& frame) {
  auto& objects = sequence_.objects[frame.index];
  objects.clear();
  for (const sim::ObjectTruth& o : frame.objects) {
    GroundTruthObject g;
    g.id = o.id;
    g.box = o.box;
    g.oriented = true;
    g.bounds = axis_aligned_bounds(o.box);
    g.moving = o.moving;
    g.parked = o.parked;
    g.visibility = o.visibility;
    objects.push_back(g);
  }
  sequence_.homographies[frame.index] = frame.homography_from_previous;
  if (sequence_.has_structures) {
    auto& structures = sequence_.structures[frame.index];
    structures.clear();
    for (const sim::StructureTruth& st : frame.structures)
      structures.push_back({st.id, sim::structure_kind_name(st.kind), st.outline});
  }
  if (keep_masks_ && !frame.object_id_mask.empty()) {
    cv::Mat mask16;
    frame.object_id_mask.convertTo(mask16, CV_16U);
    std::vector<uint8_t> png;
    if (!cv::imencode(".png", mask16, png, {cv::IMWRITE_PNG_COMPRESSION, 1})) throw InputError("cannot encode an id mask");
    (*masks_)[frame.index] = std::move(png);
  }
}

}  // namespace uavmot::eval
