#include "uavmot/sim/preview.hpp"

#include <string>

#include <opencv2/imgproc.hpp>

namespace uavmot::sim {

cv::Mat draw_ground_truth(const SimFrame& frame, const PreviewOptions& options) {
  const cv::Rect crop = options.crop.empty() ? cv::Rect(0, 0, frame.image.cols, frame.image.rows)
                                              : (options.crop & cv::Rect(0, 0, frame.image.cols, frame.image.rows));
  cv::Mat colour;
  cv::cvtColor(frame.image(crop), colour, cv::COLOR_GRAY2BGR);
  if (options.scale != 1.0) cv::resize(colour, colour, cv::Size(), options.scale, options.scale, cv::INTER_CUBIC);
  const double s = options.scale;
  const auto to_px = [&](cv::Point2d p) {
    // Continuous image coordinates -> scaled pixel centres of the crop, 4 fractional bits.
    return cv::Point(static_cast<int>((p.x - crop.x + 0.5) * s * 16.0 - 8.0), static_cast<int>((p.y - crop.y + 0.5) * s * 16.0 - 8.0));
  };
  // Structure silhouettes first, thin, so vehicle boxes stay readable on top.
  for (const StructureTruth& st : frame.structures) {
    if (!options.draw_structures) break;
    const cv::Scalar c = st.kind == StructureKind::Tree ? cv::Scalar(120, 200, 120) : cv::Scalar(200, 90, 200);
    std::vector<cv::Point> poly;
    for (const auto& p : st.outline) poly.push_back(to_px(p));
    cv::polylines(colour, poly, true, c, 1, cv::LINE_AA, 4);
  }
  for (const ObjectTruth& o : frame.objects) {
    const cv::Scalar c = o.parked ? cv::Scalar(255, 128, 0) : (o.moving ? cv::Scalar(0, 220, 0) : cv::Scalar(0, 220, 255));
    const auto corners = box_corners(o.box);
    std::vector<cv::Point> poly;
    for (const auto& p : corners) poly.push_back(to_px(p));
    cv::polylines(colour, poly, true, c, 1, cv::LINE_AA, 4);
    if (options.draw_velocity && o.moving) {
      const cv::Point2d centre(o.box.cx, o.box.cy);
      const cv::Point2d tip = centre + cv::Point2d(o.velocity_px[0], o.velocity_px[1]) * options.velocity_gain;
      cv::line(colour, to_px(centre), to_px(tip), cv::Scalar(0, 0, 255), 1, cv::LINE_AA, 4);
    }
    if (options.draw_ids) {
      cv::putText(colour, std::to_string(o.id),
                  cv::Point(static_cast<int>((o.box.cx - crop.x + o.box.length / 2 + 1) * s), static_cast<int>((o.box.cy - crop.y) * s)),
                  cv::FONT_HERSHEY_PLAIN, 0.7 * std::max(1.0, s / 1.5), c, 1, cv::LINE_AA);
    }
  }
  return colour;
}

}  // namespace uavmot::sim
