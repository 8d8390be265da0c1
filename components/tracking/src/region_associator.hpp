#pragma once
// Assignment of regions to tracks (paper IV-A): a region validates a track's Kalman prediction when
// their intersection area exceeds a small fraction of the smaller box. The result is the bipartite
// gating graph; ambiguous parts of it (one region for several tracks, several regions for one track)
// go to split and merge handling.

#include <vector>

#include "uavmot/core/oriented_box.hpp"

namespace uavmot::tracking {

struct RegionAssociation {
  std::vector<std::vector<int>> tracks_of_region;  // ascending track indices per region
  std::vector<std::vector<int>> regions_of_track;  // ascending region indices per track
  std::vector<std::vector<double>> overlap_of_track;  // intersection area, parallel to regions_of_track
};

bool gate(const OrientedBox& region, const OrientedBox& prediction, double min_intersection_fraction, double* area = nullptr);

RegionAssociation associate_regions(const std::vector<OrientedBox>& regions, const std::vector<OrientedBox>& predictions,
                                    double min_intersection_fraction);

}  // namespace uavmot::tracking
