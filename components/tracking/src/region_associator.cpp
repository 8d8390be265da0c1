#include "region_associator.hpp"

#include <algorithm>

#include "uavmot/core/spatial_grid.hpp"

namespace uavmot::tracking {

bool gate(const OrientedBox& region, const OrientedBox& prediction, double min_intersection_fraction, double* area) {
  const double inter = intersection_area(region, prediction);
  if (area != nullptr) *area = inter;
  const double smaller = std::min(box_area(region), box_area(prediction));
  return inter > 0.0 && inter >= min_intersection_fraction * smaller;
}

RegionAssociation associate_regions(const std::vector<OrientedBox>& regions, const std::vector<OrientedBox>& predictions,
                                    double min_intersection_fraction) {
  RegionAssociation result;
  result.tracks_of_region.resize(regions.size());
  result.regions_of_track.resize(predictions.size());
  result.overlap_of_track.resize(predictions.size());
  SpatialGrid grid;
  for (size_t t = 0; t < predictions.size(); ++t) grid.insert(static_cast<int>(t), axis_aligned_bounds(predictions[t]));
  for (size_t r = 0; r < regions.size(); ++r) {
    for (const int t : grid.query(axis_aligned_bounds(regions[r]))) {
      double area = 0.0;
      if (!gate(regions[r], predictions[static_cast<size_t>(t)], min_intersection_fraction, &area)) continue;
      result.tracks_of_region[r].push_back(t);
      result.regions_of_track[static_cast<size_t>(t)].push_back(static_cast<int>(r));
      result.overlap_of_track[static_cast<size_t>(t)].push_back(area);
    }
  }
  return result;
}

}  // namespace uavmot::tracking
