#include "uavmot/dds/downlink_convert.hpp"

#include <cmath>

#include "uavmot/dds/chain_convert.hpp"

namespace uavmot::dds {
namespace {

msg::CompactBox box_to_msg(const OrientedBox& b) {
  msg::CompactBox m;
  m.cx(static_cast<float>(b.cx));
  m.cy(static_cast<float>(b.cy));
  m.width(static_cast<float>(b.width));
  m.length(static_cast<float>(b.length));
  m.angle_deg(static_cast<float>(b.angle_deg));
  return m;
}

OrientedBox box_from_msg(const msg::CompactBox& m) { return {m.cx(), m.cy(), m.width(), m.length(), m.angle_deg()}; }

// The same limits as the full samples (chain_convert.cpp).
bool sane(const OrientedBox& b) {
  return is_finite(b) && b.width >= 0.0 && b.length >= 0.0 && b.width < 1e5 && b.length < 1e5 &&
         std::abs(b.cx) < 1e6 && std::abs(b.cy) < 1e6;
}

bool bad_header(int64_t index, size_t count, size_t max, const char* what, std::string& why) {
  if (index < 1) {
    why = "frame index " + std::to_string(index) + " < 1";
    return true;
  }
  if (count > max) {
    why = std::string(what) + ": " + std::to_string(count) + " entries exceed the limit of " + std::to_string(max);
    return true;
  }
  return false;
}

}  // namespace

msg::MotionSummary to_downlink_msg(const MotionEstimate& motion) {
  msg::MotionSummary m;
  m.stream_id(motion.stream_id);
  m.frame_index(motion.frame_index);
  m.capture_time_ns(motion.capture_time_ns);
  m.image_width(static_cast<uint32_t>(motion.image_width));
  m.image_height(static_cast<uint32_t>(motion.image_height));
  m.homography(to_row_major(motion.homography));
  m.valid(motion.quality.valid);
  m.inliers(motion.quality.inliers);
  m.residual_px(static_cast<float>(motion.quality.residual_px));
  m.end_of_stream(false);
  return m;
}

std::optional<MotionEstimate> from_msg(const msg::MotionSummary& m, std::string& why) {
  if (bad_header(m.frame_index(), 0, 0, "", why)) return std::nullopt;
  if (m.image_width() > 65536 || m.image_height() > 65536) {
    why = "image size " + std::to_string(m.image_width()) + "x" + std::to_string(m.image_height()) + " out of range";
    return std::nullopt;
  }
  MotionEstimate motion;
  motion.stream_id = m.stream_id().to_string();
  motion.frame_index = m.frame_index();
  motion.capture_time_ns = m.capture_time_ns();
  motion.image_width = static_cast<int>(m.image_width());
  motion.image_height = static_cast<int>(m.image_height());
  motion.homography = from_row_major(m.homography());
  if (!is_finite(motion.homography) || !std::isfinite(m.residual_px())) {
    why = "homography or residual is not finite";
    return std::nullopt;
  }
  motion.quality = {m.valid(), m.inliers(), m.residual_px()};
  return motion;
}

msg::RegionList to_downlink_msg(const SegmentationResult& s) {
  msg::RegionList m;
  m.stream_id(s.stream_id);
  m.frame_index(s.frame_index);
  m.capture_time_ns(s.capture_time_ns);
  m.end_of_stream(false);
  m.regions().reserve(s.regions.size());
  for (const auto& r : s.regions) {
    msg::CompactRegion mr;
    mr.box(box_to_msg(r.box));
    mr.score(static_cast<float>(r.score));
    mr.method(static_cast<uint8_t>(r.method));
    m.regions().push_back(mr);
  }
  return m;
}

std::optional<SegmentationResult> from_msg(const msg::RegionList& m, std::string& why) {
  if (bad_header(m.frame_index(), m.regions().size(), kMaxRegions, "regions", why)) return std::nullopt;
  SegmentationResult s;
  s.stream_id = m.stream_id().to_string();
  s.frame_index = m.frame_index();
  s.capture_time_ns = m.capture_time_ns();
  s.regions.reserve(m.regions().size());
  for (const auto& mr : m.regions()) {
    Region r{box_from_msg(mr.box()), static_cast<SegmentationMethod>(mr.method()), mr.score(), -1};
    if (!sane(r.box) || !std::isfinite(r.score) || mr.method() > static_cast<uint8_t>(SegmentationMethod::Fusion)) {
      why = "region with an invalid box, score or method";
      return std::nullopt;
    }
    s.regions.push_back(r);
  }
  return s;
}

msg::CompactTrackList to_downlink_msg(const TrackList& t) {
  msg::CompactTrackList m;
  m.stream_id(t.stream_id);
  m.frame_index(t.frame_index);
  m.capture_time_ns(t.capture_time_ns);
  m.end_of_stream(false);
  m.tracks().reserve(t.tracks.size());
  for (const auto& track : t.tracks) {
    msg::CompactTrack mt;
    mt.id(track.id);
    mt.state(static_cast<msg::TrackState>(static_cast<uint8_t>(track.state)));
    mt.box(box_to_msg(track.box));
    mt.vx(static_cast<float>(track.velocity[0]));
    mt.vy(static_cast<float>(track.velocity[1]));
    m.tracks().push_back(mt);
  }
  return m;
}

std::optional<TrackList> from_msg(const msg::CompactTrackList& m, std::string& why) {
  if (bad_header(m.frame_index(), m.tracks().size(), kMaxTracks, "tracks", why)) return std::nullopt;
  TrackList t;
  t.stream_id = m.stream_id().to_string();
  t.frame_index = m.frame_index();
  t.capture_time_ns = m.capture_time_ns();
  t.tracks.reserve(m.tracks().size());
  for (const auto& mt : m.tracks()) {
    Track track;
    track.id = mt.id();
    const auto state = static_cast<uint8_t>(mt.state());
    track.state = static_cast<TrackState>(state);
    track.box = box_from_msg(mt.box());
    track.velocity = {mt.vx(), mt.vy()};
    if (!sane(track.box) || state > static_cast<uint8_t>(TrackState::Coasting) || !std::isfinite(mt.vx()) ||
        !std::isfinite(mt.vy())) {
      why = "track " + std::to_string(mt.id()) + " has an invalid box, state or velocity";
      return std::nullopt;
    }
    t.tracks.push_back(std::move(track));
  }
  return t;
}

}  // namespace uavmot::dds
