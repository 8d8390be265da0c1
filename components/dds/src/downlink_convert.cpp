#include "uavmot/dds/downlink_convert.hpp"

#include <cmath>
#include <limits>

#include "uavmot/core/error.hpp"
#include "uavmot/core/result_files.hpp"
#include "uavmot/dds/chain_convert.hpp"

#include "sample_checks.hpp"

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

// The region as regions.txt prints it, if its numbers fit the compact fields. Valid regions
// always do: |cx| < 1e6 and sides < 1e5 px keep the bounds' thousandths under 2^31, and scores
// are fractions of features (0..1).
std::optional<msg::CompactRegion> region_to_msg(const Region& r) {
  PrintedRegion p;
  try {
    p = printed_region(r);
  } catch (const InvalidArgument&) {
    return std::nullopt;
  }
  auto fits = [](int64_t v) { return v >= std::numeric_limits<int32_t>::min() && v <= std::numeric_limits<int32_t>::max(); };
  if (!fits(p.x) || !fits(p.y) || !fits(p.width) || !fits(p.height) || p.score < 0 ||
      p.score > std::numeric_limits<uint16_t>::max()) {
    return std::nullopt;
  }
  msg::CompactRegion m;
  m.x(static_cast<int32_t>(p.x));
  m.y(static_cast<int32_t>(p.y));
  m.width(static_cast<int32_t>(p.width));
  m.height(static_cast<int32_t>(p.height));
  m.score(static_cast<uint16_t>(p.score));
  m.method(static_cast<uint8_t>(r.method));
  return m;
}

using detail::sane;  // the same limits as the full samples

int64_t capture_time_of(const FrameParts& p) {
  if (p.tracks) return p.tracks->capture_time_ns;
  if (p.segmentation) return p.segmentation->capture_time_ns;
  return p.motion ? p.motion->capture_time_ns : 0;
}

}  // namespace

msg::FrameResults to_downlink_msg(const std::string& stream_id, int64_t frame_index, const FrameParts& parts,
                                  DownlinkDrops* drops) {
  msg::FrameResults m;
  m.stream_id(stream_id);
  m.frame_index(frame_index);
  m.capture_time_ns(capture_time_of(parts));
  m.end_of_stream(false);
  if (const auto& motion = parts.motion) {
    m.has_motion(true);
    m.motion().image_width(static_cast<uint32_t>(motion->image_width));
    m.motion().image_height(static_cast<uint32_t>(motion->image_height));
    m.motion().homography(to_row_major(motion->homography));
    m.motion().valid(motion->quality.valid);
    m.motion().inliers(motion->quality.inliers);
    m.motion().residual_px(static_cast<float>(motion->quality.residual_px));
  }
  if (const auto& segmentation = parts.segmentation) {
    m.has_regions(true);
    m.regions().reserve(segmentation->regions.size());
    for (const auto& r : segmentation->regions) {
      if (auto mr = region_to_msg(r)) {
        m.regions().push_back(*mr);
      } else if (drops) {
        ++drops->regions;
      }
    }
  }
  if (const auto& tracks = parts.tracks) {
    m.has_tracks(true);
    m.tracks().reserve(tracks->tracks.size());
    for (const auto& track : tracks->tracks) {
      if (track.id > std::numeric_limits<uint32_t>::max()) {
        if (drops) ++drops->tracks;
        continue;
      }
      msg::CompactTrack mt;
      mt.id(static_cast<uint32_t>(track.id));
      mt.state(static_cast<msg::TrackState>(static_cast<uint8_t>(track.state)));
      mt.box(box_to_msg(track.box));
      mt.vx(static_cast<float>(track.velocity[0]));
      mt.vy(static_cast<float>(track.velocity[1]));
      if (drops && !is_float32_exact(track)) ++drops->inexact_tracks;
      m.tracks().push_back(mt);
    }
  }
  return m;
}

std::optional<GroundFrame> from_msg(const msg::FrameResults& m, std::string& why) {
  if (detail::bad_index(m.frame_index(), why)) return std::nullopt;
  if (m.regions().size() > kMaxRegions || m.tracks().size() > kMaxTracks) {
    why = std::to_string(m.regions().size()) + " regions / " + std::to_string(m.tracks().size()) + " tracks exceed the limits";
    return std::nullopt;
  }
  GroundFrame parts;
  const std::string stream = m.stream_id().to_string();
  if (m.has_motion()) {
    const auto& mm = m.motion();
    if (mm.image_width() > 65536 || mm.image_height() > 65536) {
      why = "image size " + std::to_string(mm.image_width()) + "x" + std::to_string(mm.image_height()) + " out of range";
      return std::nullopt;
    }
    MotionEstimate motion;
    motion.stream_id = stream;
    motion.frame_index = m.frame_index();
    motion.capture_time_ns = m.capture_time_ns();
    motion.image_width = static_cast<int>(mm.image_width());
    motion.image_height = static_cast<int>(mm.image_height());
    motion.homography = from_row_major(mm.homography());
    if (!is_finite(motion.homography) || !std::isfinite(mm.residual_px())) {
      why = "homography or residual is not finite";
      return std::nullopt;
    }
    motion.quality = {mm.valid(), mm.inliers(), mm.residual_px()};
    parts.motion = std::move(motion);
  }
  if (m.has_regions()) {
    std::vector<PrintedRegion> regions;
    regions.reserve(m.regions().size());
    for (const auto& mr : m.regions()) {
      if (mr.width() < 0 || mr.height() < 0 || !is_segmentation_method(mr.method())) {
        why = "region with a negative size or an invalid method";
        return std::nullopt;
      }
      regions.push_back({mr.x(), mr.y(), mr.width(), mr.height(), mr.score()});
    }
    parts.regions = std::move(regions);
  } else if (!m.regions().empty()) {
    why = "regions without has_regions";
    return std::nullopt;
  }
  if (m.has_tracks()) {
    TrackList t;
    t.stream_id = stream;
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
    parts.tracks = std::move(t);
  } else if (!m.tracks().empty()) {
    why = "tracks without has_tracks";
    return std::nullopt;
  }
  return parts;
}

}  // namespace uavmot::dds
