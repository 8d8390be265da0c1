#pragma once
// Draws the static 3-D structures through the full pinhole camera, after the ground and the
// vehicles: painter's algorithm (farthest structure first, by depth along the optical axis),
// each face a textured planar quad or polygon warped into its bounding box only. A pixel a
// structure covers by at least half is cleared in the vehicle id mask, so the mask keeps only
// what is seen of each vehicle.

#include <memory>
#include <vector>

#include <opencv2/core/mat.hpp>
#include <opencv2/core/matx.hpp>
#include <opencv2/core/types.hpp>

#include "structure_layout.hpp"
#include "uavmot/sim/scenario.hpp"
#include "uavmot/sim/simulator.hpp"

namespace uavmot::sim::detail {

class StructureRenderer {
 public:
  StructureRenderer(const std::vector<Structure>& structures, const StructureParams& params);
  ~StructureRenderer();
  StructureRenderer(StructureRenderer&&) noexcept;
  StructureRenderer& operator=(StructureRenderer&&) noexcept;

  bool empty() const;
  // image: CV_32F; id_mask: CV_32S. `projection` is K [R | t] (world -> image px), `camera_m`
  // the camera centre. Returns the structures at least partly in view, by id.
  std::vector<StructureTruth> render(cv::Mat& image, cv::Mat& id_mask, const cv::Matx34d& projection,
                                     cv::Point3d camera_m) const;

 private:
  struct Face;
  struct Solid;
  std::vector<Solid> solids_;
  std::vector<cv::Mat> textures_;
};

}  // namespace uavmot::sim::detail
