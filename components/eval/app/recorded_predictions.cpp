#include "recorded_predictions.hpp"

#include <map>

#include <spdlog/spdlog.h>

#include "uavmot/core/error.hpp"
#include "uavmot/mcap/reader.hpp"
#include "uavmot/record/recorded_chain.hpp"

namespace uavmot::eval {

Predictions load_recorded_predictions(const std::string& path, const std::string& stream_id, const SequenceInfo& info) {
  // uavmot/motion is optional (a recording of the tracks alone still scores the tracking).
  bool has_motion = false;
  {
    mcap::Reader reader;
    reader.open(path);
    for (const auto& [id, channel] : reader.channels()) has_motion = has_motion || channel.topic == "uavmot/motion";
  }
  std::map<std::string, Predictions> streams;
  auto check_frame = [&](int64_t frame, const char* topic) {
    if (frame < 1 || frame > info.length) {
      throw InputError(path + ": " + topic + " has frame " + std::to_string(frame) + ", outside the sequence (1.." +
                       std::to_string(info.length) + ")");
    }
  };
  record::RecordedSampleHandlers handlers;
  handlers.tracks = [&](const TrackList& t) {
    check_frame(t.frame_index, "uavmot/tracks");
    streams[t.stream_id].add_tracks(t);
  };
  if (has_motion) {
    handlers.motion = [&](const MotionEstimate& m) {
      check_frame(m.frame_index, "uavmot/motion");
      streams[m.stream_id].add_motion(m);
    };
  }
  const auto counts = record::read_recorded_samples(path, handlers);
  if (!counts.damage.empty()) {
    if (counts.tracks == 0) throw InputError(counts.damage);
    spdlog::warn("{} (scoring the {} track lists before it)", counts.damage, counts.tracks);
  }
  if (counts.invalid > 0) spdlog::warn("{}: {} invalid samples skipped", path, counts.invalid);
  if (counts.tracks == 0) throw InputError(path + ": no track lists recorded on uavmot/tracks");
  if (stream_id.empty()) {
    if (streams.size() == 1) return std::move(streams.begin()->second);
    std::string names;
    for (const auto& [id, p] : streams) names += (names.empty() ? "" : ", ") + id;
    throw InputError(path + " holds several streams (" + names + "): choose one with --stream-id");
  }
  const auto it = streams.find(stream_id);
  if (it == streams.end()) throw InputError(path + ": no stream '" + stream_id + "' in the recording");
  return std::move(it->second);
}

}  // namespace uavmot::eval
