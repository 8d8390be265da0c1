#include "uavmot/dds/chain_convert.hpp"

#include <cmath>

#include "sample_checks.hpp"

namespace uavmot::dds {
namespace {

using detail::bad_index;
using detail::sane;

msg::OrientedBox box_to_msg(const OrientedBox& b) {
  msg::OrientedBox m;
  m.cx(b.cx);
  m.cy(b.cy);
  m.width(b.width);
  m.length(b.length);
  m.angle_deg(b.angle_deg);
  return m;
}

OrientedBox box_from_msg(const msg::OrientedBox& m) { return {m.cx(), m.cy(), m.width(), m.length(), m.angle_deg()}; }

bool finite(double v) { return std::isfinite(v); }

template <class Seq>
bool too_long(const Seq& seq, size_t max, const char* what, std::string& why) {
  if (seq.size() <= max) return false;
  why = std::string(what) + ": " + std::to_string(seq.size()) + " entries exceed the limit of " + std::to_string(max);
  return true;
}

}  // namespace

msg::MotionEstimate to_msg(const MotionEstimate& motion) {
  msg::MotionEstimate m;
  m.stream_id(motion.stream_id);
  m.frame_index(motion.frame_index);
  m.capture_time_ns(motion.capture_time_ns);
  m.image_width(static_cast<uint32_t>(motion.image_width));
  m.image_height(static_cast<uint32_t>(motion.image_height));
  m.homography(to_row_major(motion.homography));
  m.valid(motion.quality.valid);
  m.inliers(motion.quality.inliers);
  m.residual_px(motion.quality.residual_px);
  m.end_of_stream(false);
  m.features().reserve(motion.features.size());
  for (const auto& f : motion.features) {
    msg::Feature mf;
    mf.id(f.id);
    mf.x(f.position.x);
    mf.y(f.position.y);
    mf.vx(f.velocity[0]);
    mf.vy(f.velocity[1]);
    mf.velocity_sigma(f.velocity_sigma);
    mf.age(f.age);
    mf.moving(f.moving);
    m.features().push_back(mf);
  }
  return m;
}

std::optional<MotionEstimate> from_msg(const msg::MotionEstimate& m, std::string& why) {
  if (bad_index(m.frame_index(), why) || too_long(m.features(), kMaxFeatures, "features", why)) return std::nullopt;
  MotionEstimate motion;
  motion.stream_id = m.stream_id().to_string();
  motion.frame_index = m.frame_index();
  motion.capture_time_ns = m.capture_time_ns();
  if (m.image_width() > 65536 || m.image_height() > 65536) {
    why = "image size " + std::to_string(m.image_width()) + "x" + std::to_string(m.image_height()) + " out of range";
    return std::nullopt;
  }
  motion.image_width = static_cast<int>(m.image_width());
  motion.image_height = static_cast<int>(m.image_height());
  motion.homography = from_row_major(m.homography());
  if (!is_finite(motion.homography)) {
    why = "homography is not finite";
    return std::nullopt;
  }
  motion.quality = {m.valid(), m.inliers(), m.residual_px()};
  motion.features.reserve(m.features().size());
  for (const auto& mf : m.features()) {
    if (!finite(mf.x()) || !finite(mf.y()) || !finite(mf.vx()) || !finite(mf.vy()) || !finite(mf.velocity_sigma())) {
      why = "feature " + std::to_string(mf.id()) + " has a non-finite value";
      return std::nullopt;
    }
    motion.features.push_back({mf.id(), {mf.x(), mf.y()}, {mf.vx(), mf.vy()}, mf.velocity_sigma(), mf.age(), mf.moving()});
  }
  return motion;
}

msg::Segmentation to_msg(const SegmentationResult& s) {
  msg::Segmentation m;
  m.stream_id(s.stream_id);
  m.frame_index(s.frame_index);
  m.capture_time_ns(s.capture_time_ns);
  m.end_of_stream(false);
  for (const auto& c : s.clusters) {
    msg::FeatureCluster mc;
    mc.id(c.id);
    mc.box(box_to_msg(c.box));
    mc.vx(c.velocity[0]);
    mc.vy(c.velocity[1]);
    mc.feature_ids(c.feature_ids);
    m.clusters().push_back(mc);
  }
  for (const auto& r : s.regions) {
    msg::Region mr;
    mr.box(box_to_msg(r.box));
    mr.method(static_cast<msg::SegmentationMethod>(static_cast<uint8_t>(r.method)));
    mr.score(r.score);
    mr.cluster_id(r.cluster_id);
    m.regions().push_back(mr);
  }
  return m;
}

std::optional<SegmentationResult> from_msg(const msg::Segmentation& m, std::string& why) {
  if (bad_index(m.frame_index(), why) || too_long(m.clusters(), kMaxClusters, "clusters", why) ||
      too_long(m.regions(), kMaxRegions, "regions", why)) {
    return std::nullopt;
  }
  SegmentationResult s;
  s.stream_id = m.stream_id().to_string();
  s.frame_index = m.frame_index();
  s.capture_time_ns = m.capture_time_ns();
  for (const auto& mc : m.clusters()) {
    FeatureCluster c;
    c.id = mc.id();
    c.box = box_from_msg(mc.box());
    c.velocity = {mc.vx(), mc.vy()};
    if (!sane(c.box) || !finite(mc.vx()) || !finite(mc.vy()) ||
        too_long(mc.feature_ids(), kMaxIdsPerObject, "cluster feature ids", why)) {
      if (why.empty()) why = "cluster " + std::to_string(mc.id()) + " has an invalid box or velocity";
      return std::nullopt;
    }
    c.feature_ids = mc.feature_ids();
    s.clusters.push_back(std::move(c));
  }
  for (const auto& mr : m.regions()) {
    const auto method = static_cast<uint64_t>(mr.method());  // all of it: 256 is no method either
    Region r{box_from_msg(mr.box()), static_cast<SegmentationMethod>(method), mr.score(), mr.cluster_id()};
    if (!sane(r.box) || !finite(r.score) || !is_segmentation_method(method)) {
      why = "region with an invalid box, score or method";
      return std::nullopt;
    }
    s.regions.push_back(r);
  }
  return s;
}

msg::TrackList to_msg(const TrackList& t) {
  msg::TrackList m;
  m.stream_id(t.stream_id);
  m.frame_index(t.frame_index);
  m.capture_time_ns(t.capture_time_ns);
  m.end_of_stream(false);
  for (const auto& track : t.tracks) {
    msg::Track mt;
    mt.id(track.id);
    mt.state(static_cast<msg::TrackState>(static_cast<uint8_t>(track.state)));
    mt.box(box_to_msg(track.box));
    mt.vx(track.velocity[0]);
    mt.vy(track.velocity[1]);
    mt.sigma_x(track.sigma_x);
    mt.sigma_y(track.sigma_y);
    mt.sigma_width(track.sigma_width);
    mt.sigma_length(track.sigma_length);
    mt.sigma_angle_deg(track.sigma_angle_deg);
    mt.age(track.age);
    mt.frames_since_update(track.frames_since_update);
    mt.feature_ids(track.feature_ids);
    m.tracks().push_back(mt);
  }
  return m;
}

std::optional<TrackList> from_msg(const msg::TrackList& m, std::string& why) {
  if (bad_index(m.frame_index(), why) || too_long(m.tracks(), kMaxTracks, "tracks", why)) return std::nullopt;
  TrackList t;
  t.stream_id = m.stream_id().to_string();
  t.frame_index = m.frame_index();
  t.capture_time_ns = m.capture_time_ns();
  for (const auto& mt : m.tracks()) {
    Track track;
    track.id = mt.id();
    const auto state = static_cast<uint8_t>(mt.state());
    track.state = static_cast<TrackState>(state);
    track.box = box_from_msg(mt.box());
    track.velocity = {mt.vx(), mt.vy()};
    track.sigma_x = mt.sigma_x();
    track.sigma_y = mt.sigma_y();
    track.sigma_width = mt.sigma_width();
    track.sigma_length = mt.sigma_length();
    track.sigma_angle_deg = mt.sigma_angle_deg();
    track.age = mt.age();
    track.frames_since_update = mt.frames_since_update();
    if (!sane(track.box) || state > static_cast<uint8_t>(TrackState::Coasting) || !finite(mt.vx()) || !finite(mt.vy()) ||
        too_long(mt.feature_ids(), kMaxIdsPerObject, "track feature ids", why)) {
      if (why.empty()) why = "track " + std::to_string(mt.id()) + " has an invalid box, state or velocity";
      return std::nullopt;
    }
    track.feature_ids = mt.feature_ids();
    t.tracks.push_back(std::move(track));
  }
  return t;
}

}  // namespace uavmot::dds
