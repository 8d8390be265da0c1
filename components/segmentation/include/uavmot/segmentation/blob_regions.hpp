#pragma once
// From accumulators to oriented blobs (paper III-B/C): normalisation to [0, 255], spatial fusion,
// quantile-based adaptive threshold, connected components, per-component closing, and the
// best-fitting oriented box of each blob.

#include <vector>

#include <opencv2/core/mat.hpp>

#include "uavmot/core/oriented_box.hpp"
#include "uavmot/segmentation/segmentation_options.hpp"

namespace uavmot::segmentation {

// acc * 255 / max(max(acc), reference_max): the window's strongest response maps to 255 unless
// it is weaker than `reference_max` (a minimum-contrast edge), so noise is not stretched.
cv::Mat normalise_accumulator(const cv::Mat& acc, double reference_max);

// Pixelwise sum of normalised accumulators (range [0, 255 n]), or their product scaled back
// to [0, 255]. All inputs must have the same size and type CV_32F.
cv::Mat fuse_accumulators(const std::vector<cv::Mat>& normalised, FusionRule rule);

// The `quantile` quantile (0..1) of the accumulator's values (to within 1/4096 of its maximum,
// from a histogram), but at least `min_value`.
double adaptive_threshold(const cv::Mat& acc, double quantile, double min_value);

struct Blob {
  OrientedBox box;             // in the accumulator's pixel frame, shrunk by the edge band
  double mean_strength = 0.0;  // mean accumulator value over the blob's above-threshold pixels
  int pixel_count = 0;         // above-threshold pixels
};

// Splitting of blobs larger than one vehicle: such a component is thresholded again, on its own
// pixels, at `levels` evenly spaced values between the threshold and its peak; at the first
// level where it falls apart into two or more parts of at least `min_part_pixels`, those parts
// replace it. Limits <= 0 disable the test.
struct SplitRule {
  double max_length_px = 0.0;
  double max_width_px = 0.0;
  int levels = 4;
  int min_part_pixels = 6;
};

// Thresholds `acc` (pixels >= threshold and > 0), labels 4- or 8-connected components, closes and
// hole-fills each component on its own (so closing never joins two components), fits an
// oriented box to each (see BoxFit), minus `edge_band_px` on every side, and splits components
// that `split` finds too large. Components with fewer than `min_pixels` are ignored. Blobs come
// in label order (raster order of their first pixel), split parts in place of their parent.
std::vector<Blob> extract_blobs(const cv::Mat& acc, double threshold, int closing_size_px, double edge_band_px,
                                BoxFit fit = BoxFit::Moments, int connectivity = 8, int min_pixels = 3,
                                const SplitRule& split = {});

// Groups the blobs of one window that are parts of one vehicle (windscreen, roof and bonnet of a
// car give separate outlines): blobs are taken largest first; one joins the first group it
// touches (boxes grown by `touch_px` intersect) whose combined box (minimum-area rectangle of all
// corners) stays within max_length_px x max_width_px. Returns one box per group, in the order
// the groups were started. Limits <= 0 disable grouping.
struct GroupedBlob {
  OrientedBox box;
  int pixel_count = 0;
  int parts = 0;
};
std::vector<GroupedBlob> group_vehicle_parts(const std::vector<Blob>& blobs, double max_length_px, double max_width_px,
                                             double touch_px = 1.5);

}  // namespace uavmot::segmentation
