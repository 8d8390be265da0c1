#pragma once
// Kalman update with a region (full box) or a reconstructed centre (paper IV-C/D), and with the
// velocity and heading of the track's linked features.
// The axis angle is compared modulo 180 deg (axis_angle_difference_deg), and a region whose
// width/length labelling is swapped relative to the track (a near-square box reported with the other
// side as length) is relabelled before the update.

#include "kalman_model.hpp"

namespace uavmot::tracking {

// The region's box expressed with the width/length labelling closest to `predicted`.
OrientedBox align_box_labelling(const OrientedBox& measured, const OrientedBox& predicted);

KalmanState update_with_box(const KalmanState& state, const OrientedBox& measured, const BoxMeasurementNoise& noise,
                            double min_box_size_px);

// Before updating with a region after a split, the old size is no longer evidence: widen the size
// variance by the squared size innovation so the filter adopts the new size within a few frames.
void open_size_uncertainty(KalmanState& state, const OrientedBox& measured);

// `region` re-described in the frame of a known direction of travel: angle = heading; length and
// width = the mean of the extents of its rectangle and of its inscribed ellipse along and across it.
// A vehicle's length lies along its travel, whatever way a blob of windows or shadow is elongated.
OrientedBox box_along_heading(const OrientedBox& region, double heading_deg);

// `box` lengthened along its axis, no wider, until it reaches `margin` px beyond every point's
// projection on the axis, but to no more than `max_length`. The vehicle's own features lie on it,
// even where its blob does not.
OrientedBox lengthen_to_cover(const OrientedBox& box, const std::vector<cv::Point2d>& points, double margin,
                              double max_length);

// The ground velocity measured directly (the linked features' median velocity), 1-sigma per axis.
KalmanState update_with_velocity(const KalmanState& state, const cv::Vec2d& velocity, double sigma_px);

// The box's axis angle measured by the direction of travel (deg, compared modulo 180).
KalmanState update_with_heading(const KalmanState& state, double heading_deg, double sigma_deg);

KalmanState update_with_position(const KalmanState& state, const cv::Point2d& centre, double sigma_px);

}  // namespace uavmot::tracking
