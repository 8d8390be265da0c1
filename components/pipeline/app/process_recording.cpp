#include "process_recording.hpp"

#include <chrono>
#include <filesystem>
#include <map>
#include <memory>
#include <set>

#include <spdlog/spdlog.h>

#include "uavmot/core/app.hpp"
#include "uavmot/core/result_files.hpp"
#include "uavmot/core/stream_id.hpp"
#include "uavmot/record/recorded_chain.hpp"
#include "uavmot/tracking/tracker.hpp"

namespace uavmot::pipeline {

int process_recording(const std::string& recording, const std::string& out_dir, ChainOptions options) {
  const auto start = std::chrono::steady_clock::now();
  // A first pass only lists the streams, so one stream writes into out_dir as `process` does.
  // Stream ids name folders: ids that are not a safe folder name are left out, with an error.
  std::set<std::string> stream_ids, bad_ids;
  record::read_recorded_chain(recording, [&](const std::string& stream, const MotionEstimate&, const SegmentationResult&) {
    (is_valid_stream_id(stream) ? stream_ids : bad_ids).insert(stream);
  });
  for (const auto& id : bad_ids) {
    spdlog::error("{}: left out stream {}: {}", recording, printable_stream_id(id), stream_id_problem(id));
  }

  struct Stream {
    std::unique_ptr<tracking::Tracker> tracker;
    std::unique_ptr<ResultFilesWriter> files;
  };
  std::map<std::string, Stream> streams;
  const auto counts = record::read_recorded_chain(
      recording, [&](const std::string& id, const MotionEstimate& motion, const SegmentationResult& segmentation) {
        if (stream_ids.count(id) == 0) return;
        auto [it, fresh] = streams.try_emplace(id);
        Stream& s = it->second;
        if (fresh) {
          ResultFilesOptions o;
          o.directory = stream_ids.size() > 1 ? (std::filesystem::path(out_dir) / id).string() : out_dir;
          o.fps = options.scene.fps;
          o.gsd_m = options.scene.gsd_m;
          s.files = std::make_unique<ResultFilesWriter>(o);
          s.tracker = std::make_unique<tracking::Tracker>(options.tracking, options.scene);
          spdlog::info("stream '{}' -> {}", id, o.directory);
        }
        const TrackList tracks = s.tracker->process(motion, segmentation);
        s.files->write_motion(motion);
        s.files->write_segmentation(segmentation);
        s.files->write_tracks(tracks);
      });
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  for (auto& [id, s] : streams) {
    RunSummary summary;
    summary.input = recording;
    summary.wall_time_s = seconds;
    s.files->close(summary);
  }
  spdlog::info("{}: tracked {} frames of {} stream(s) from the recording in {:.1f} s", recording, counts.pairs,
               streams.size(), seconds);
  if (counts.unpaired > 0) spdlog::warn("{} frames had only one of motion and segmentation recorded", counts.unpaired);
  if (!counts.damage.empty()) {
    spdlog::error("{}", counts.damage);
    return kExitBadInput;
  }
  if (!bad_ids.empty()) return kExitBadInput;
  if (streams.empty()) {
    spdlog::error("{}: no frame with both a motion estimate and a segmentation result", recording);
    return kExitBadInput;
  }
  return kExitOk;
}

}  // namespace uavmot::pipeline
