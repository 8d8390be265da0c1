#pragma once
// Parameters of the object segmentation layer (paper section III). Lengths that describe the
// scene are in metres and converted with SceneInfo's GSD; filter scales are in pixels because
// they describe image structure (edge width), not object size.

#include <vector>

#include "uavmot/core/chain_types.hpp"
#include "uavmot/core/yaml_config.hpp"

namespace uavmot::segmentation {

// Local feature clustering (paper III-A): single linkage over position and relative velocity.
struct ClusteringOptions {
  // Two moving features are linked when they are at most this far apart (metres on the ground)
  // AND their velocities differ by at most the speed threshold below. Single linkage chains
  // links, so a car's features only need to be linked pairwise through their neighbours.
  double link_distance_m = 3.0;
  // Largest relative velocity difference (m/s) of linked features. It is raised to
  // `velocity_sigma_factor` times the combined 1-sigma velocity noise of the pair when that is
  // larger, so noisy sub-pixel velocities do not shatter one car into several clusters.
  double link_speed_difference_mps = 2.5;
  double velocity_sigma_factor = 3.0;
  // Clusters with fewer moving features are dropped. 1 by default: the motion layer keeps
  // features at least 10 px apart, so a 15 x 5 px car often carries a single moving feature.
  int min_features = 1;
};

// The three gradient segmentations (paper III-B); each writes its own accumulator.
struct GradientOptions {
  // Korn gradient: Gaussian-derivative filters normalised to a unit step response of 1, one
  // per scale; the accumulator is the sum of the magnitudes over these sigmas (px).
  std::vector<double> korn_sigmas_px = {0.7, 1.0, 1.4};
  // Morphological gradient, eq. (1): sum over square structuring elements of these side
  // lengths (odd, px) of dilation minus erosion. Default is the single 3 x 3 element: with
  // {3, 5} the 5 x 5 term widens the band by a pixel on each side, which bridges the ~4 px gap
  // between cars driving side by side at the paper's scale (docs/segmentation.md has figures).
  std::vector<int> morphological_sizes_px = {3};
  // LBP gradient, eq. (2): riu2 patterns with this many neighbours on circles of these radii
  // (px); accepted texture primitives add the neighbours' standard deviation.
  int lbp_neighbours = 8;
  std::vector<double> lbp_radii_px = {1.0, 2.0};
  // Neighbourhoods whose standard deviation (grey levels) is below this are flat/noise and
  // never texture primitives.
  double lbp_min_stddev = 4.0;
};

enum class FusionRule { Sum, Product };

// How a blob becomes an oriented box. MinAreaRect: cv::minAreaRect of the blob's outline, grown
// by one pixel (pixel centres -> pixel extent); exact for axis-aligned blobs but, on a rotated
// object, the staircase of the pixel grid makes it about a pixel too large per dimension.
// Moments: the rectangle with the filled blob's centroid, principal axes and second moments;
// unbiased at any angle and less pulled by a stray pixel on the outline.
enum class BoxFit { Moments, MinAreaRect };

// Spatial fusion, thresholding and blob -> region conversion (paper III-B/C).
struct RegionOptions {
  // The image window around a cluster is its box's bounds plus this margin (metres).
  double window_margin_m = 2.0;
  // Accumulators are mapped to [0, 255] by dividing by their window maximum, but never by less
  // than the response to a step edge of this contrast (grey levels): a window that holds only
  // noise stays dark instead of being stretched to full scale.
  double min_edge_contrast = 12.0;
  // Sum (paper default) or pixelwise product of the normalised accumulators (method=fusion).
  FusionRule fusion_rule = FusionRule::Sum;
  // Adaptive threshold: the `threshold_quantile` quantile of the window's accumulator values,
  // but at least `threshold_min_fraction` of the accumulator's full scale.
  double threshold_quantile = 0.75;
  double threshold_min_fraction = 0.2;
  // Pixel connectivity of the connected components: 4, 8, or 0 = by method: 8 for lbp (its
  // accumulator is sparse, accepted pixels often touch only diagonally) and 4 for the dense
  // korn, morphological and fusion accumulators (8 would leak across the thin diagonal gap
  // between two cars driving side by side at an oblique angle).
  int connectivity = 0;
  // Side (px, odd) of the square element used to close each connected component on its own
  // (components are labelled first, so closing never joins two of them).
  int closing_size_px = 3;
  BoxFit box_fit = BoxFit::Moments;
  // A gradient blob is the object's outline thickened by the filters: its box is shrunk by
  // this much (px) on every side to return the object's own extent.
  double edge_band_px = 1.0;
  // A blob wider than split_width_factor x the vehicle width, or longer than
  // split_length_factor x its length (after the edge band), is re-thresholded on its own pixels
  // to split it into vehicles (two cars side by side whose outlines touch); 0 disables. Width
  // only by default: a car with its shadow is ~1.5 widths wide, a truck up to ~2.7 car lengths.
  double split_width_factor = 2.0;
  double split_length_factor = 0.0;
  // Blobs of one window that come within group_touch_px of each other and together fit in
  // group_length_factor x vehicle length by group_width_factor x vehicle width are parts of one
  // vehicle and become one region (the windscreen and roof of a car give separate outlines; on a
  // car painted like the road only its windows stand out, a few pixels apart); 0 disables. A
  // touch distance of 3 px instead of 1.5 px raised the chain's correct rate on `paper` seeds 1-3
  // by 2.0, 1.9 and 0.2 points (docs/segmentation.md).
  double group_length_factor = 1.3;
  double group_width_factor = 1.5;
  double group_touch_px = 3.0;
  // A region whose supporting features' mean lies more than this fraction of its width to one
  // side of its centre line is moved across onto them: the blob took in static texture beside the
  // vehicle, e.g. the lane marking along a road-grey car (docs/segmentation.md); 0 disables.
  double recentre_min_offset_fraction = 0.2;
  // A region whose cluster the shift check tests is moved onto where its pixels move with the
  // cluster: the centroid of that evidence over the region grown by this many vehicle widths, when
  // less than motion_evidence_max_inside of it lies inside the region and the centroid lies at
  // least motion_evidence_min_offset_px from the region's centre (a road-grey car's blob is its
  // shadow and the marking beside it; docs/segmentation.md, "Motion evidence"); 0 disables.
  double motion_evidence_margin_widths = 1.0;
  double motion_evidence_max_inside = 0.6;
  double motion_evidence_min_offset_px = 0.5;
  // A cluster whose window gives no blob gets, instead of the box around its features, its box moved
  // onto its motion evidence, searched `fallback_evidence_lengths` vehicle lengths past each end and
  // `fallback_evidence_widths` vehicle widths each side: a dark car whose edges vanish into a shadow
  // or the asphalt often shows a single feature at one end, and the box around that sits half a car
  // off. Kept only where the previous frame shifted by the cluster's velocity explains the box's
  // pixels with at most `fallback_evidence_max_ratio` of the error at rest (a stricter shift check:
  // the best of several shifts beats rest on plain asphalt by chance); it is then reported with the
  // segmentation's method, not as method=clustering, since the image placed it
  // (docs/segmentation.md, "Blob-less clusters"). fallback_evidence_lengths 0 disables.
  double fallback_evidence_lengths = 0.5;
  double fallback_evidence_widths = 0.5;
  double fallback_evidence_max_ratio = 0.75;
  // Plausible region sizes, as multiples of the expected vehicle length / width.
  double min_length_factor = 0.4;
  double max_length_factor = 3.0;
  double min_width_factor = 0.3;
  double max_width_factor = 3.0;
  // A blob is kept only when at least `min_supporting_features` of its cluster's features lie
  // inside its box grown by `support_margin_px`.
  int min_supporting_features = 1;
  double support_margin_px = 1.5;
  // When no blob of a cluster is plausible and supported, return the cluster's box instead
  // (marked method=clustering) so that a low-contrast object is not lost; likewise, when at
  // least max(2, min_features) of a cluster's features lie farther than support_margin_px plus
  // half a vehicle width from every kept region, add the box around those features (a second
  // car whose blob was rejected).
  bool fallback_to_cluster_box = true;
  // A gradient region of a cluster faster than `shift_check_min_speed_px` (px/frame) is dropped
  // when the previous frame, carried through the homography, matches its pixels unshifted at
  // least as well as shifted by the cluster's velocity, times `shift_check_ratio`: static texture
  // in the cluster's window (a lane marking beside a car). 0 disables; it needs the previous
  // frame, so the first frame of a run and frames after a gap are not checked.
  double shift_check_ratio = 1.1;
  double shift_check_min_speed_px = 0.3;
  // The moving hypothesis also tries the velocity +- this much in x and y (the features' velocity is
  // an estimate); shifts slower than shift_check_min_speed_px are never tried.
  double shift_check_search_px = 0.5;
  // A region whose box is covered by an earlier region's box for more than this fraction of
  // its area is a duplicate (nested blob, or the same blob seen from two cluster windows).
  double duplicate_overlap = 0.5;
  // In sunlight a vehicle's blob is its body and its shadow, so every box sits half a shadow toward
  // the shadow's side. The shadow's image offset is learnt from the regions (bright bodies, the dark
  // band at the box's far end; docs/segmentation.md, "Shadows") and each gradient region's centre
  // moves back by `shadow_correction_factor` x that offset (0 disables). Offsets are searched up to
  // `shadow_max_m`; a region votes when its body's upper quartile is `shadow_bright_margin` grey
  // levels above the road around it; the frame's offset is used once `shadow_min_regions` of its
  // regions have voted, the two halves of the votes find offsets within `shadow_agreement_px` and the
  // shadow band is on average more than `shadow_min_darkness` grey levels darker than the road.
  double shadow_correction_factor = 1.0;
  // ... and each such box, body and shadow, shrinks by `shadow_size_correction_factor` x the
  // offset's extent along its length and across it, to the body's own size (0 disables).
  double shadow_size_correction_factor = 1.0;
  double shadow_max_m = 2.0;
  double shadow_bright_margin = 15.0;
  int shadow_min_regions = 10;
  double shadow_agreement_px = 1.0;
  double shadow_min_darkness = 0.0;
};

struct SegmentationOptions {
  // clustering | korn | morphological | lbp | fusion: the rows of the paper's Tables I and II.
  SegmentationMethod method = SegmentationMethod::Fusion;
  ClusteringOptions clustering;
  GradientOptions gradients;
  RegionOptions regions;
};

// Throws InvalidArgument naming the field when a value is out of its domain.
void validate(const SegmentationOptions& options);

// Reads a `segmentation:` section (flat keys, the field names above; `method` and
// `fusion_rule` as strings). Unknown keys and out-of-range values throw InputError.
SegmentationOptions load_segmentation_options(const ConfigNode& node);

}  // namespace uavmot::segmentation
