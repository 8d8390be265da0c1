#pragma once
// The ground under one video frame, from a decoded metadata packet and the image size:
// - the four corners on the ground (MISB order: point 1 = upper left of the image, then
//   clockwise: 2 upper right, 3 lower right, 4 lower left), from the full corners (ST 0601 tags
//   82-89, EG 0104 corners) when all are there, else from the frame centre plus offsets (26-33);
// - a homography from image pixels to local east/north metres around the frame centre
//   (local_tangent_plane.hpp), through the image's outer corners in the house's continuous frame
//   (docs/conventions.md): (-0.5, -0.5) -> point 1, (w - 0.5, -0.5) -> 2, (w - 0.5, h - 0.5) -> 3,
//   (-0.5, h - 0.5) -> 4. A plane-to-plane homography is exact for a pinhole camera over flat
//   ground, so pixels in between map as the camera saw them;
// - the ground sample distance at the image centre, from the first source available:
//   footprint (the homography's Jacobian there: the mean of the ground metres one pixel spans
//   along x and along y), else slant range and horizontal FOV (2 R tan(hfov / 2) / width, exact at
//   the centre across the line of sight), else target width / width.

#include <array>
#include <optional>

#include <opencv2/core/matx.hpp>
#include <opencv2/core/types.hpp>

#include "uavmot/geo/local_tangent_plane.hpp"
#include "uavmot/geo/uas_metadata.hpp"

namespace uavmot::geo {

enum class GsdSource { kNone, kFootprint, kSlantRangeFov, kTargetWidth };
const char* to_string(GsdSource source);

class FrameGeometry {
 public:
  // Throws InvalidArgument when the image size is not positive.
  static FrameGeometry from_metadata(const UasMetadata& metadata, cv::Size image_size);

  cv::Size image_size() const { return image_size_; }
  // Ground corners 1-4 (upper left, upper right, lower right, lower left); nullopt without them.
  const std::optional<std::array<LatLon, 4>>& corners() const { return corners_; }
  std::optional<LatLon> frame_center() const { return center_; }

  // Pixel <-> ground: only when the corners give a non-degenerate homography.
  bool has_ground_mapping() const { return image_to_ground_.has_value(); }
  // nullopt without a mapping, or for a pixel at or beyond the horizon.
  std::optional<LatLon> pixel_to_lat_lon(cv::Point2d pixel) const;
  std::optional<cv::Point2d> lat_lon_to_pixel(LatLon point) const;
  // Image pixels -> east/north metres on plane(), h33 = 1.
  const std::optional<cv::Matx33d>& image_to_ground() const { return image_to_ground_; }
  const LocalTangentPlane& plane() const { return plane_; }

  std::optional<double> gsd_m_per_px() const { return gsd_; }
  GsdSource gsd_source() const { return gsd_source_; }
  // Footprint GSD along the image x and y axes at the centre (oblique views differ a lot).
  std::optional<double> gsd_x_m_per_px() const { return gsd_x_; }
  std::optional<double> gsd_y_m_per_px() const { return gsd_y_; }

 private:
  FrameGeometry(cv::Size image_size, LatLon origin) : image_size_(image_size), plane_(origin) {}

  cv::Size image_size_;
  LocalTangentPlane plane_;
  std::optional<std::array<LatLon, 4>> corners_;
  std::optional<LatLon> center_;
  std::optional<cv::Matx33d> image_to_ground_;
  std::optional<cv::Matx33d> ground_to_image_;
  std::optional<double> gsd_;
  std::optional<double> gsd_x_;
  std::optional<double> gsd_y_;
  GsdSource gsd_source_ = GsdSource::kNone;
};

// The image's outer corners in the continuous frame, in MISB corner order.
std::array<cv::Point2d, 4> image_corners(cv::Size image_size);
// The centre of the image in the continuous frame: ((w - 1) / 2, (h - 1) / 2).
cv::Point2d image_center(cv::Size image_size);

// The four corners of a packet: full corners if all eight values are there, else centre +
// offsets if those are; nullopt otherwise or when a latitude/longitude is out of range.
std::optional<std::array<LatLon, 4>> ground_corners(const UasMetadata& metadata);

}  // namespace uavmot::geo
