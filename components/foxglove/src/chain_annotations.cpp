#include "uavmot/foxglove/chain_annotations.hpp"

#include <cstring>

#include <opencv2/imgcodecs.hpp>

#include "uavmot/core/error.hpp"
#include "uavmot/core/oriented_box.hpp"
#include "uavmot/view/overlay.hpp"

namespace uavmot::foxglove {
namespace {

// uavmot-view's colours (BGR scalars) as Foxglove RGBA, so both drawings agree.
Color colour(const cv::Scalar& bgr, double alpha = 1.0) { return {bgr[2] / 255.0, bgr[1] / 255.0, bgr[0] / 255.0, alpha}; }
const Color kTransparent{0.0, 0.0, 0.0, 0.0};

PointsAnnotation polygon(const OrientedBox& box, const Time& stamp, const Color& outline, double thickness) {
  PointsAnnotation p;
  p.timestamp = stamp;
  p.type = PointsType::LineLoop;
  for (const auto& c : box_corners(box)) p.points.push_back({c.x, c.y});
  p.outline_color = outline;
  p.fill_color = kTransparent;
  p.thickness = thickness;
  return p;
}

}  // namespace

ImageAnnotations annotate_tracks(const TrackList& tracks, const AnnotationStyle& style) {
  ImageAnnotations out;
  const Time stamp = time_from_ns(tracks.capture_time_ns);
  for (const auto& track : tracks.tracks) {
    const bool tentative = track.state == TrackState::Tentative;
    if (tentative && !style.tentative_tracks) continue;
    const bool coasting = track.state == TrackState::Coasting;
    const Color c = colour(tentative ? view::kTentativeTrackColour : view::kConfirmedTrackColour, coasting ? 0.6 : 1.0);
    out.points.push_back(polygon(track.box, stamp, c, tentative || coasting ? 1.0 : 2.0));
    if (tentative) continue;  // no label, as in uavmot-view: most tentative tracks never confirm
    TextAnnotation label;
    label.timestamp = stamp;
    const auto bounds = axis_aligned_bounds(track.box);
    label.position = {bounds.x, bounds.y - 2.0};  // bottom-left of the text, just above the box
    label.text = "#" + std::to_string(track.id) + " " + view::format_speed(track.velocity, style.gsd_m, style.fps);
    label.font_size = 12.0;
    label.text_color = colour(view::kConfirmedTrackColour);
    label.background_color = {0.0, 0.0, 0.0, 0.6};
    out.texts.push_back(std::move(label));
  }
  return out;
}

ImageAnnotations annotate_segmentation(const SegmentationResult& segmentation) {
  ImageAnnotations out;
  const Time stamp = time_from_ns(segmentation.capture_time_ns);
  for (const auto& cluster : segmentation.clusters) out.points.push_back(polygon(cluster.box, stamp, colour(view::kClusterColour), 1.0));
  for (const auto& region : segmentation.regions) out.points.push_back(polygon(region.box, stamp, colour(view::kRegionColour), 1.0));
  return out;
}

ImageAnnotations annotate_motion(const MotionEstimate& motion, const AnnotationStyle& style) {
  ImageAnnotations out;
  const Time stamp = time_from_ns(motion.capture_time_ns);
  PointsAnnotation moving, vectors, stationary;
  moving.timestamp = vectors.timestamp = stationary.timestamp = stamp;
  moving.type = stationary.type = PointsType::Points;
  vectors.type = PointsType::LineList;
  moving.outline_color = vectors.outline_color = colour(view::kMovingFeatureColour);
  stationary.outline_color = colour(view::kStationaryFeatureColour);
  moving.fill_color = vectors.fill_color = stationary.fill_color = kTransparent;
  moving.thickness = stationary.thickness = 3.0;  // point diameter
  vectors.thickness = 1.0;
  for (const auto& f : motion.features) {
    const Point2 at{f.position.x, f.position.y};
    if (f.moving) {
      moving.points.push_back(at);
      vectors.points.push_back(at);
      vectors.points.push_back({at.x + f.velocity[0] * style.vector_scale, at.y + f.velocity[1] * style.vector_scale});
    } else if (style.stationary_features) {
      stationary.points.push_back(at);
    }
  }
  for (auto* p : {&moving, &vectors, &stationary}) {
    if (!p->points.empty()) out.points.push_back(std::move(*p));
  }
  return out;
}

ImageAnnotations annotate_printed_regions(const std::vector<PrintedRegion>& regions, int64_t capture_time_ns) {
  ImageAnnotations out;
  const Time stamp = time_from_ns(capture_time_ns);
  for (const auto& r : regions) {
    const double x = static_cast<double>(r.x) / 1000.0, y = static_cast<double>(r.y) / 1000.0;
    const double w = static_cast<double>(r.width) / 1000.0, h = static_cast<double>(r.height) / 1000.0;
    PointsAnnotation p;
    p.timestamp = stamp;
    p.type = PointsType::LineLoop;
    p.points = {{x, y}, {x + w, y}, {x + w, y + h}, {x, y + h}};
    p.outline_color = colour(view::kRegionColour);
    p.fill_color = kTransparent;
    p.thickness = 1.0;
    out.points.push_back(std::move(p));
  }
  return out;
}

ImageFormat parse_image_format(const std::string& name) {
  if (name == "jpeg") return ImageFormat::Jpeg;
  if (name == "raw") return ImageFormat::Raw;
  throw InvalidArgument("image format '" + name + "' is not jpeg or raw");
}

const char* to_string(ImageFormat format) { return format == ImageFormat::Jpeg ? "jpeg" : "raw"; }

RawImage raw_image(const Frame& frame) {
  const cv::Mat& image = frame.image;
  if (image.type() != CV_8UC1 && image.type() != CV_8UC3) throw InputError("frame " + std::to_string(frame.index) + ": not mono8 or bgr8");
  RawImage out;
  out.timestamp = time_from_ns(frame.capture_time_ns);
  out.frame_id = frame.stream_id;
  out.width = static_cast<uint32_t>(image.cols);
  out.height = static_cast<uint32_t>(image.rows);
  out.encoding = image.channels() == 1 ? "mono8" : "bgr8";
  out.step = static_cast<uint32_t>(image.cols * image.elemSize());
  out.data.resize(static_cast<size_t>(out.step) * out.height);
  for (int y = 0; y < image.rows; ++y) std::memcpy(out.data.data() + static_cast<size_t>(y) * out.step, image.ptr(y), out.step);
  return out;
}

CompressedImage jpeg_image(const Frame& frame, int quality) {
  std::vector<uint8_t> jpeg;
  if (frame.image.empty() || !cv::imencode(".jpg", frame.image, jpeg, {cv::IMWRITE_JPEG_QUALITY, quality})) {
    throw InputError("frame " + std::to_string(frame.index) + ": cannot encode as JPEG");
  }
  return jpeg_image(frame.stream_id, frame.capture_time_ns, std::move(jpeg));
}

CompressedImage jpeg_image(const std::string& stream_id, int64_t capture_time_ns, std::vector<uint8_t> jpeg) {
  CompressedImage out;
  out.timestamp = time_from_ns(capture_time_ns);
  out.frame_id = stream_id;
  out.data = std::move(jpeg);
  out.format = "jpeg";
  return out;
}

}  // namespace uavmot::foxglove
