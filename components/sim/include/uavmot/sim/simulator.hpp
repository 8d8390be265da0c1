#pragma once
// Renders a simulated UAV sequence frame by frame, with exact ground truth:
//
//   uavmot::sim::Simulator sim(uavmot::sim::preset_scenario("paper"), 42);
//   uavmot::sim::SimFrame frame;
//   while (sim.next(frame)) { ... frame.image, frame.homography_from_previous, frame.objects ... }
//
// Each frame is a warp of one ground raster by a known ground->image homography G_k, so the
// true frame-to-frame homography H_k = G_k * G_{k-1}^-1 is exact for the background.

#include <cstdint>
#include <memory>
#include <vector>

#include <opencv2/core/mat.hpp>
#include <opencv2/core/matx.hpp>
#include <opencv2/core/types.hpp>

#include "uavmot/core/homography.hpp"
#include "uavmot/core/oriented_box.hpp"
#include "uavmot/core/scene_info.hpp"
#include "uavmot/sim/scenario.hpp"

namespace uavmot::sim {

enum class VehicleKind : uint8_t { Car = 0, Van = 1, Truck = 2 };

// Ground truth for one vehicle that is at least partly inside the image.
struct ObjectTruth {
  int id = 0;              // from 1, stable over the sequence, shared by the id mask
  bool moving = false;     // ground speed >= traffic.moving_threshold_mps in this frame
  bool parked = false;     // a parked vehicle: never moves
  OrientedBox box;         // true footprint in the image (continuous coordinates)
  cv::Vec2d velocity_px;   // motion relative to the ground, in px/frame of this image
  // Fraction of the footprint that is seen: inside the image and not hidden by a building,
  // tree or wall (0 = entirely hidden; the vehicle is still listed while inside the image).
  double visibility = 1.0;
  VehicleKind kind = VehicleKind::Car;
  double speed_mps = 0.0;  // ground speed
};

enum class StructureKind : uint8_t { Building = 0, Tree = 1, Wall = 2 };
const char* structure_kind_name(StructureKind kind);  // "building", "tree", "wall"

// A static 3-D structure that is at least partly inside the image: its silhouette (roof,
// walls, canopy, trunk) as the convex hull of its projected 3-D outline, whether or not
// another structure hides part of it.
struct StructureTruth {
  int id = 0;  // from 1, fixed for the sequence (own numbering, not vehicle ids)
  StructureKind kind = StructureKind::Building;
  double height_m = 0.0;
  std::vector<cv::Point2d> outline;  // convex, image px (continuous coordinates), not clipped to the image
};

struct SimFrame {
  int64_t index = 0;  // from 1
  cv::Mat image;      // CV_8UC1, exactly what is written to the JPEG file (decoded)
  Homography homography_from_previous = Homography::eye();  // frame k-1 -> k, h33 = 1; identity for frame 1
  Homography ground_to_image = Homography::eye();           // ground raster px -> image px
  std::vector<ObjectTruth> objects;                         // ordered by id
  // CV_32S, 0 background, else the id of the vehicle covering >= half the pixel; pixels a
  // structure covers by at least half are 0 (only the visible part of a vehicle is marked).
  cv::Mat object_id_mask;
  std::vector<StructureTruth> structures;  // in view, ordered by id; empty in a flat world
  std::vector<uint8_t> encoded_jpeg;  // the JPEG bytes `image` was decoded from
};

class Simulator {
 public:
  // Throws InputError when the scenario is invalid or the texture folder cannot be read.
  Simulator(Scenario scenario, uint64_t seed);
  ~Simulator();
  Simulator(Simulator&&) noexcept;
  Simulator& operator=(Simulator&&) noexcept;

  // Renders the next frame; false once frame_count() frames have been produced.
  bool next(SimFrame& frame);
  int frame_count() const;
  SceneInfo scene() const;
  const Scenario& scenario() const;
  uint64_t seed() const;
  // Totals seen so far: distinct vehicle ids that were visible, of those moving at least once, parked.
  int vehicles_seen() const;
  int moving_vehicles_seen() const;
  int parked_vehicles_seen() const;

 private:
  class Impl;
  std::unique_ptr<Impl> impl_;
};

// Id of the vehicle at `point` in the frame: the mask value at the nearest pixel, or, within
// `tolerance_px`, the nearest mask pixel of a vehicle; 0 when there is none.
int object_at(const SimFrame& frame, cv::Point2d point, double tolerance_px = 0.0);
// The truth entry for `id`, or nullptr.
const ObjectTruth* find_object(const SimFrame& frame, int id);
// True when `point` lies on (within tolerance of) a vehicle that is moving in this frame.
bool is_on_moving_object(const SimFrame& frame, cv::Point2d point, double tolerance_px = 1.0);

}  // namespace uavmot::sim
