#include "tracker_state_io.hpp"

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

#include "tracker_statePubSubTypes.h"
#include "uavmot/core/durable_file.hpp"
#include "uavmot/core/error.hpp"
#include "uavmot/dds/cdr_sample.hpp"

namespace uavmot::tracking {
namespace {

// Version 2 added TrackRecordState.origin, version 3 travel_from; files of other versions are
// refused, not misread (version 1 files have no mark).
constexpr char kFileMagic[8] = {'U', 'T', 'R', 'K', 'S', 'T', 'A', 'T'};
constexpr uint32_t kFileVersion = 3;
constexpr size_t kFileHeaderBytes = sizeof kFileMagic + sizeof(uint32_t);

msg::TrackRecordState record_to_msg(const TrackRecord& r) {
  msg::TrackRecordState m;
  m.id(r.id);
  m.state(static_cast<msg::TrackState>(static_cast<uint8_t>(r.state)));
  m.mean(r.mean);
  m.covariance(r.covariance);
  m.age(r.age);
  m.hits(r.hits);
  m.hit_history(r.hit_history);
  m.frames_since_update(r.frames_since_update);
  m.frames_dormant(r.frames_dormant);
  msg::OrientedBox box;
  box.cx(r.anchor_box.cx);
  box.cy(r.anchor_box.cy);
  box.width(r.anchor_box.width);
  box.length(r.anchor_box.length);
  box.angle_deg(r.anchor_box.angle_deg);
  m.anchor_box(box);
  m.origin({r.origin.x, r.origin.y});
  m.travel_from({r.travel_from.x, r.travel_from.y});
  for (const auto& f : r.features) {
    msg::FeatureLinkState fm;
    fm.feature_id(f.feature_id);
    fm.u(f.box_uv.x);
    fm.v(f.box_uv.y);
    fm.frames_linked(f.frames_linked);
    m.features().push_back(fm);
  }
  return m;
}

std::optional<TrackRecord> record_from_msg(const msg::TrackRecordState& m, std::string& why) {
  TrackRecord r;
  r.id = m.id();
  const auto state = static_cast<uint8_t>(m.state());
  if (state > static_cast<uint8_t>(TrackState::Coasting)) {
    why = "track " + std::to_string(m.id()) + " has an unknown state";
    return std::nullopt;
  }
  r.state = static_cast<TrackState>(state);
  r.mean = m.mean();
  r.covariance = m.covariance();
  r.age = m.age();
  r.hits = m.hits();
  r.hit_history = m.hit_history();
  r.frames_since_update = m.frames_since_update();
  r.frames_dormant = m.frames_dormant();
  const auto& b = m.anchor_box();
  r.anchor_box = {b.cx(), b.cy(), b.width(), b.length(), b.angle_deg()};
  if (!std::isfinite(m.origin()[0]) || !std::isfinite(m.origin()[1])) {
    why = "track " + std::to_string(m.id()) + " has a non-finite origin";
    return std::nullopt;
  }
  r.origin = {m.origin()[0], m.origin()[1]};
  if (!std::isfinite(m.travel_from()[0]) || !std::isfinite(m.travel_from()[1])) {
    why = "track " + std::to_string(m.id()) + " has a non-finite travel_from";
    return std::nullopt;
  }
  r.travel_from = {m.travel_from()[0], m.travel_from()[1]};
  for (const auto& fm : m.features()) {
    if (!std::isfinite(fm.u()) || !std::isfinite(fm.v())) {
      why = "track " + std::to_string(m.id()) + " has a non-finite feature link";
      return std::nullopt;
    }
    r.features.push_back({fm.feature_id(), {fm.u(), fm.v()}, fm.frames_linked()});
  }
  return r;
}

}  // namespace

msg::TrackerSnapshot to_msg(const TrackerState& state, const std::string& stream_id, int64_t frame_index) {
  msg::TrackerSnapshot m;
  m.stream_id(stream_id);
  m.frame_index(frame_index);
  m.next_id(state.next_id);
  m.frames_processed(state.frames_processed);
  m.rejected_homographies(state.rejected_homographies);
  m.rejected_regions(state.rejected_regions);
  m.rejected_features(state.rejected_features);
  for (const auto& r : state.tracks) m.tracks().push_back(record_to_msg(r));
  for (const auto& r : state.dormant) m.dormant().push_back(record_to_msg(r));
  return m;
}

std::optional<TrackerState> from_msg(const msg::TrackerSnapshot& m, std::string& why) {
  TrackerState state;
  state.next_id = m.next_id();
  state.frames_processed = m.frames_processed();
  state.rejected_homographies = m.rejected_homographies();
  state.rejected_regions = m.rejected_regions();
  state.rejected_features = m.rejected_features();
  for (const auto* list : {&m.tracks(), &m.dormant()}) {
    for (const auto& rm : *list) {
      auto r = record_from_msg(rm, why);
      if (!r) return std::nullopt;
      (list == &m.tracks() ? state.tracks : state.dormant).push_back(std::move(*r));
    }
  }
  return state;
}

void save_snapshot(const msg::TrackerSnapshot& snapshot, const std::string& path) {
  auto copy = snapshot;  // the generated serializer takes a mutable sample
  std::vector<uint8_t> bytes;
  try {
    bytes = dds::to_cdr<msg::TrackerSnapshotPubSubType>(copy);
  } catch (const InputError& e) {
    throw OutputError("cannot encode the tracker state for '" + path + "': " + e.what());
  }
  uint8_t header[kFileHeaderBytes];
  std::memcpy(header, kFileMagic, sizeof kFileMagic);
  std::memcpy(header + sizeof kFileMagic, &kFileVersion, sizeof kFileVersion);  // little-endian hosts only
  bytes.insert(bytes.begin(), header, header + kFileHeaderBytes);
  write_file_durably(path, bytes);
}

std::optional<msg::TrackerSnapshot> load_snapshot(const std::string& path) {
  if (!std::filesystem::exists(path)) return std::nullopt;
  std::ifstream in(path, std::ios::binary);
  const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (bytes.size() < kFileHeaderBytes || std::memcmp(bytes.data(), kFileMagic, sizeof kFileMagic) != 0) {
    throw InputError("tracker state file '" + path + "' has no 'UTRKSTAT' mark: it is damaged or from a uavmot "
                     "before format version 2 (remove it to start this stream afresh)");
  }
  uint32_t version = 0;
  std::memcpy(&version, bytes.data() + sizeof kFileMagic, sizeof version);
  if (version != kFileVersion) {
    throw InputError("tracker state file '" + path + "' is of format version " + std::to_string(version) +
                     "; this build reads version " + std::to_string(kFileVersion) + " (remove it to start this stream afresh)");
  }
  msg::TrackerSnapshotPubSubType type;
  msg::TrackerSnapshot snapshot;
  dds::from_cdr(type, bytes.data() + kFileHeaderBytes, bytes.size() - kFileHeaderBytes, snapshot,
                "tracker state file '" + path + "' is corrupt");
  return snapshot;
}

}  // namespace uavmot::tracking
