// uavmot-sink: subscribes to motion, segmentation and tracks and writes the same files as
// `uavmot process` (tracks.txt, tracks_obb.csv, homographies.txt, features.csv, clusters.txt,
// regions.txt, summary.json) through the same writer, so lossless runs are byte-identical.
// With --downlink it reads what crosses an air -> ground link instead: uavmot/downlink/results,
// one compact sample per frame (no features or clusters; exact, docs/deployment.md), and
// with --preview-dir it also saves the link's JPEG previews (uavmot/downlink/preview) there.
// With several streams, each gets a folder of its own under --out. With --metadata VIDEO (the
// source's input, an MPEG-TS with KLV) it also writes tracks.geojson and lat,lon columns, as
// `uavmot process` does (docs/geo.md).
// Stream ids come from the wire: only valid ids of this run are written (uavmot/sink/stream_gate.hpp).
// With --stream-timeout a stream (a UAV) silent that long is given up as lost: the run goes on and
// ends with the other streams' ends (uavmot/sink/stream_liveness.hpp), and exits 1 to say so.
// A result file that cannot be written (a full disk) ends the run with exit 1; the files keep
// every complete line written before. With --resume a restarted sink continues the unfinished run
// in --out: its files keep every whole frame, and frames that come again are skipped.

#include <algorithm>
#include <filesystem>
#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <set>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "downlinkPubSubTypes.h"
#include "framePubSubTypes.h"
#include "motionPubSubTypes.h"
#include "segmentationPubSubTypes.h"
#include "tracksPubSubTypes.h"
#include "uavmot/core/app.hpp"
#include "uavmot/core/error.hpp"
#include "uavmot/core/output_file.hpp"
#include "uavmot/core/result_files.hpp"
#include "uavmot/core/shutdown.hpp"
#include "uavmot/core/stream_id.hpp"
#include "uavmot/dds/chain_convert.hpp"
#include "uavmot/dds/downlink_convert.hpp"
#include "uavmot/dds/health_reporter.hpp"
#include "uavmot/dds/node_options.hpp"
#include "uavmot/dds/node_support.hpp"
#include "uavmot/dds/upstream_watch.hpp"
#include "uavmot/geo/chain_ground.hpp"
#include "uavmot/geo/track_map.hpp"
#include "uavmot/sink/stream_gate.hpp"
#include "uavmot/sink/stream_liveness.hpp"
#include "uavmot/source/frame_source.hpp"

namespace uavmot {
namespace {

struct SinkOptions {
  std::string out_dir;
  double gsd_m = 0.0, fps = 25.0, idle_timeout_s = 0.0, stream_timeout_s = 0.0, upstream_timeout_s = 0.0;
  int streams = 1;
  std::vector<std::string> stream_ids;  // --stream-id: only these
  bool downlink = false;
  bool resume = false;      // continue the unfinished run in out_dir
  std::string preview_dir;  // downlink: save the JPEG previews here
  std::string metadata;     // the source's input video, for its flight metadata
  std::string gsd_source;   // summary.json: flag, klv, or empty (no GSD)
  const geo::ChainGround* ground = nullptr;  // with --metadata: the ground under each frame
};

// Saves the JPEG previews of the run's streams as PREVIEW_DIR/STREAM_FRAME.jpg. A preview that
// arrives before its stream's first results waits (a few) until the results bind the stream.
class PreviewSaver {
 public:
  PreviewSaver(dds::Participant& participant, const std::string& dir, sink::StreamGate& gate,
               const std::vector<std::string>& stream_ids)
      : dir_(dir), gate_(gate),
        reader_(participant.make_reader<msg::FramePubSubType>(dds::kDownlinkPreviewTopic, dds::TopicClass::Preview, stream_ids)) {
    std::filesystem::create_directories(dir_);
  }
  bool pump() {
    for (auto it = pending_.begin(); it != pending_.end();) {
      if (gate_.is_bound(it->stream_id().to_string())) {
        save(*it);
        it = pending_.erase(it);
      } else {
        ++it;
      }
    }
    msg::Frame sample;
    bool any = false;
    while (reader_->take(sample)) {
      any = true;
      if (sample.encoding() != msg::Encoding::JPEG || sample.data().empty()) continue;
      switch (gate_.check(reader_->topic(), sample.stream_id().to_string())) {
        case sink::StreamGate::Verdict::Bound: save(sample); break;
        case sink::StreamGate::Verdict::Unbound:
          pending_.push_back(sample);
          if (pending_.size() > kMaxPending) pending_.pop_front();  // its stream never came: nothing lost
          break;
        case sink::StreamGate::Verdict::Refused: break;  // counted and logged by the gate
      }
    }
    return any;
  }
  dds::TopicReader<msg::FramePubSubType>& reader() { return *reader_; }
  uint64_t images() const { return images_; }

 private:
  static constexpr size_t kMaxPending = 16;
  void save(const msg::Frame& sample) {
    const std::string name = fmt::format("{}/{}_{:06d}.jpg", dir_, sample.stream_id().to_string(), sample.frame_index());
    write_output_file(name, std::string_view(reinterpret_cast<const char*>(sample.data().data()), sample.data().size()));
    ++images_;
  }

  std::string dir_;
  sink::StreamGate& gate_;
  std::unique_ptr<dds::TopicReader<msg::FramePubSubType>> reader_;
  std::deque<msg::Frame> pending_;
  uint64_t images_ = 0;
};

// The result files of every stream, one folder each when several are expected.
class ResultFolders {
 public:
  explicit ResultFolders(const SinkOptions& o) : o_(o) {}

  // STREAM must be bound by the StreamGate: its id is a safe folder name.
  ResultFilesWriter& of(const std::string& stream) {
    auto [it, fresh] = writers_.try_emplace(stream);
    if (fresh) {
      ResultFilesOptions r;
      r.directory = o_.streams > 1 ? (std::filesystem::path(o_.out_dir) / stream).string() : o_.out_dir;
      r.fps = o_.fps;
      r.gsd_m = o_.gsd_m;
      // The downlink carries neither features nor clusters: no empty files pretending otherwise.
      r.write_features = r.write_clusters = !o_.downlink;
      r.resume = o_.resume;
      r.resume_whole_frames = o_.downlink;  // one sample per frame, homographies.txt written last
      it->second = std::make_unique<ResultFilesWriter>(
          r, o_.ground && o_.ground->has_ground_mapping() ? o_.ground->pixel_to_lat_lon() : PixelToLatLon{});
      spdlog::info("stream '{}' -> {}", stream, r.directory);
      const ResumePoint& at = it->second->resumed_at();
      if (o_.resume && at.motion_frame + at.segmentation_frame + at.tracks_frame > 0) {
        spdlog::info("stream '{}': continuing the run in {}: it holds motion to frame {}, segmentation to {}, tracks to {}",
                     stream, r.directory, at.motion_frame, at.segmentation_frame, at.tracks_frame);
      }
    }
    return *it->second;
  }
  // Every result file of a stream gets its tracks; with ground geometry the map keeps them too.
  void write_tracks(const std::string& stream, const TrackList& tracks) {
    of(stream).write_tracks(tracks);
    if (o_.ground) track_maps_[stream].add(tracks);
  }
  // Closes every stream's files; false when one could not be written (logged), the others still close.
  bool close(double seconds) {
    bool ok = true;
    for (auto& [id, writer] : writers_) {
      try {
        close_stream(id, *writer, seconds);
      } catch (const OutputError& e) {
        spdlog::error("stream '{}': {}", id, e.what());
        ok = false;
      }
    }
    return ok;
  }

 private:
  void close_stream(const std::string& id, ResultFilesWriter& writer, double seconds) {
    RunSummary summary;
    summary.input = "dds:" + id;
    summary.wall_time_s = seconds;
    summary.gsd_source = o_.gsd_source;
    if (o_.ground && !o_.ground->flight().empty()) summary.metadata = o_.ground->summary();
    const int64_t frames = writer.frames_written();
    writer.close(summary);
    spdlog::info("stream '{}': {} frames written", id, frames);
    if (o_.ground && o_.ground->has_ground_mapping()) {
      const auto path = std::filesystem::path(writer.options().directory) / "tracks.geojson";
      const auto counts = o_.ground->write_geojson(path, track_maps_[id], o_.fps);
      spdlog::info("stream '{}': tracks.geojson with {} tracks ({} points without ground geometry)", id, counts.features,
                   counts.skipped_points);
    }
  }

  const SinkOptions& o_;
  std::map<std::string, std::unique_ptr<ResultFilesWriter>> writers_;
  std::map<std::string, geo::TrackMapRecorder> track_maps_;
};

// Runs `drain` (true when it took anything) until `finished`, the idle timeout, the upstream
// timeout or shutdown. False when the files must not be closed as a run: a result file could not be
// written, or the writers are gone for good (both logged); the files keep what was written.
// `writers` counts the writers matched on the inputs.
template <class Drain, class Finished, class Wait, class Writers>
bool sink_loop(const SinkOptions& o, dds::HealthReporter& health, Drain drain, Finished finished, Wait wait,
               Writers writers) try {
  auto last_sample = std::chrono::steady_clock::now();
  bool started = false;
  dds::UpstreamWatch upstream(o.upstream_timeout_s);
  while (!shutdown_requested() && !finished()) {
    const bool any = drain();
    health.tick();
    const auto now = std::chrono::steady_clock::now();
    if (any) {
      last_sample = now;
      started = true;
    } else {
      wait();
      if (upstream.gone(writers())) {
        spdlog::error("{}", upstream.message("the results"));
        return false;
      }
      if (started && o.idle_timeout_s > 0 && now - last_sample > std::chrono::duration<double>(o.idle_timeout_s)) {
        spdlog::error("nothing arrived for {} s; closing the files with what was received", o.idle_timeout_s);
        break;
      }
    }
  }
  return true;
} catch (const OutputError& e) {
  spdlog::error("{}; stopped writing", e.what());
  return false;
}

// Logs the streams that went silent for the timeout; they count as done from now on.
void give_up_silent_streams(sink::StreamLiveness& liveness) {
  for (const auto& id : liveness.newly_lost(std::chrono::steady_clock::now())) {
    spdlog::error("stream '{}': nothing for {} s after frame {}: given up as lost; the run goes on with the other streams "
                  "(its files keep what arrived; it is written again if it comes back before the run ends)",
                  id, liveness.timeout_s(), liveness.last_frame(id));
  }
}

// A sample of STREAM's frame FRAME_INDEX was accepted.
void heard(sink::StreamLiveness& liveness, const std::string& stream, int64_t frame_index) {
  if (liveness.heard(stream, frame_index, std::chrono::steady_clock::now())) {
    spdlog::warn("stream '{}' is back (frame {}) after it was given up as lost", stream, frame_index);
  }
}

// The exit code of a sink run: every stream ended (none lost) and every file was written.
int sink_exit_code(bool finished, bool written, const sink::StreamGate& gate, const sink::StreamLiveness& liveness) {
  gate.log_summary();
  if (!written) return kExitFailure;
  if (liveness.lost_count() > 0) {
    spdlog::error("{} stream(s) lost before their end of stream (--stream-timeout {} s)", liveness.lost_count(), liveness.timeout_s());
    return kExitFailure;
  }
  return finished ? kExitOk : kExitFailure;
}

auto log_received = [](const auto& r) { spdlog::info("{}: {} samples, {} bytes received", r.topic(), r.samples_taken(), r.bytes_taken()); };

// The full chain topics (one host): each comes from one writer, in frame order; written as they arrive.
int run_chain_sink(dds::Participant& participant, const SinkOptions& o) {
  // Resuming, the readers also get the writers' recent history (transient-local): what reached the
  // killed sink's reader but not its files arrives again, and the frames the files hold are skipped.
  const auto inputs = o.resume ? dds::TopicClass::ChainResume : dds::TopicClass::Chain;
  // With --stream-id, other ids are filtered out before they can fill the readers' instance slots.
  auto motion = participant.make_reader<msg::MotionEstimatePubSubType>(dds::kMotionTopic, inputs, o.stream_ids);
  auto segmentation = participant.make_reader<msg::SegmentationPubSubType>(dds::kSegmentationTopic, inputs, o.stream_ids);
  auto tracks = participant.make_reader<msg::TrackListPubSubType>(dds::kTracksTopic, inputs, o.stream_ids);
  dds::HealthReporter health(participant, "sink", "*");
  health.watch(*motion);
  health.watch(*segmentation);
  health.watch(*tracks);
  dds::RejectLog rejects;
  sink::StreamGate gate(o.streams, o.stream_ids);
  ResultFolders folders(o);
  sink::StreamLiveness liveness(o.stream_timeout_s);
  std::map<std::string, std::set<std::string>> ended;  // per stream: the topics that ended
  std::map<std::pair<std::string, std::string>, int64_t> last_frame;  // per stream and topic
  const auto start = std::chrono::steady_clock::now();

  auto drain = [&](auto& reader, auto write) {
    typename std::remove_reference_t<decltype(*reader)>::Sample sample;
    bool any = false;
    while (reader->take(sample)) {
      any = true;
      const std::string stream = sample.stream_id().to_string();
      if (sample.end_of_stream()) {
        if (gate.admit_end(reader->topic(), stream)) {
          if (ended[stream].insert(reader->topic()).second && ended[stream].size() == 3) liveness.ended(stream);
        } else {
          health.invalid_sample();
        }
        continue;
      }
      if (!gate.would_admit(stream)) {
        gate.admit(reader->topic(), stream);  // counts and logs the refusal
        health.invalid_sample();
        continue;
      }
      std::string why;
      auto value = dds::from_msg(sample, why);
      if (!value) {
        health.invalid_sample();
        rejects.log(reader->topic(), why);
        continue;
      }
      gate.admit(reader->topic(), stream);  // a valid sample binds its stream
      heard(liveness, stream, value->frame_index);
      ResultFilesWriter& files = folders.of(stream);
      // Deduplicate after validation: a malformed sample must not hide the valid one of its frame.
      const std::string& topic = reader->topic();
      const ResumePoint& at = files.resumed_at();
      int64_t& last = last_frame.try_emplace({stream, topic}, topic == dds::kMotionTopic         ? at.motion_frame
                                                             : topic == dds::kSegmentationTopic ? at.segmentation_frame
                                                                                                : at.tracks_frame)
                          .first->second;
      if (value->frame_index <= last) continue;  // already written (before a restart, too)
      last = value->frame_index;
      write(files, *value);
    }
    return any;
  };
  auto finished = [&] {
    size_t done = liveness.lost_count();
    for (const auto& [id, topics] : ended) done += topics.size() >= 3 ? 1 : 0;
    return static_cast<int>(done) >= o.streams;
  };
  const bool written = sink_loop(o, health, [&] {
    bool any = drain(motion, [&](ResultFilesWriter& f, const MotionEstimate& m) { f.write_motion(m); health.frame_in(); });
    any |= drain(segmentation, [](ResultFilesWriter& f, const SegmentationResult& s) { f.write_segmentation(s); });
    any |= drain(tracks, [&](ResultFilesWriter&, const TrackList& t) {
      folders.write_tracks(t.stream_id, t);
      health.frame_out(t.frame_index, 0.0, dds::latency_ms_since(t.capture_time_ns));
    });
    give_up_silent_streams(liveness);
    return any;
  }, finished, [&] { tracks->wait_for_data(std::chrono::milliseconds(50)); },
     [&] { return motion->matched() + segmentation->matched() + tracks->matched(); });
  // After a failed write no summary.json claims a complete run; the files keep their complete lines.
  const bool closed = written && folders.close(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  log_received(*motion);
  log_received(*segmentation);
  log_received(*tracks);
  health.report(closed ? msg::ComponentState::FINISHED : msg::ComponentState::FAILED);
  return sink_exit_code(finished(), closed, gate, liveness);
}

// The link (air -> ground): one sample per frame with what the UAV's chain produced of it.
int run_downlink_sink(dds::Participant& participant, const SinkOptions& o) {
  // With --stream-id, other ids are filtered out before they can fill the reader's instance slots.
  auto results =
      participant.make_reader<msg::FrameResultsPubSubType>(dds::kDownlinkResultsTopic, dds::TopicClass::Downlink, o.stream_ids);
  dds::HealthReporter health(participant, "sink", "*");
  health.watch(*results);
  sink::StreamGate gate(o.streams, o.stream_ids);
  std::unique_ptr<PreviewSaver> preview;
  if (!o.preview_dir.empty()) {
    preview = std::make_unique<PreviewSaver>(participant, o.preview_dir, gate, o.stream_ids);
    health.watch(preview->reader());
  }
  dds::RejectLog rejects;
  ResultFolders folders(o);
  sink::StreamLiveness liveness(o.stream_timeout_s);
  std::map<std::string, int64_t> last_frame;  // per stream
  std::set<std::string> ended;
  const auto start = std::chrono::steady_clock::now();

  auto drain = [&] {
    msg::FrameResults sample;
    bool any = false;
    while (results->take(sample)) {
      any = true;
      const std::string stream = sample.stream_id().to_string();
      if (sample.end_of_stream()) {
        if (gate.admit_end(results->topic(), stream)) {
          ended.insert(stream);
          liveness.ended(stream);
        } else {
          health.invalid_sample();
        }
        continue;
      }
      if (!gate.would_admit(stream)) {
        gate.admit(results->topic(), stream);  // counts and logs the refusal
        health.invalid_sample();
        continue;
      }
      std::string why;
      auto parts = dds::from_msg(sample, why);
      if (!parts) {
        health.invalid_sample();
        rejects.log(results->topic(), why);
        continue;
      }
      gate.admit(results->topic(), stream);  // a valid sample binds its stream
      heard(liveness, stream, sample.frame_index());
      ResultFilesWriter& files = folders.of(stream);
      // The writer's history, sent again after the link was lost and found (transient-local),
      // repeats frames already written.
      int64_t& last = last_frame.try_emplace(stream, files.resumed_at().motion_frame).first->second;
      if (sample.frame_index() <= last) continue;
      last = sample.frame_index();
      if (parts->regions) files.write_printed_regions(sample.frame_index(), *parts->regions);
      if (parts->tracks) folders.write_tracks(stream, *parts->tracks);
      // Last: homographies.txt marks the frame whole for a sink that continues after a crash.
      if (parts->motion) {
        files.write_motion(*parts->motion);
        health.frame_in();
      }
      health.frame_out(sample.frame_index(), 0.0, dds::latency_ms_since(sample.capture_time_ns()));
    }
    if (preview) any |= preview->pump();
    give_up_silent_streams(liveness);
    return any;
  };
  auto finished = [&] { return static_cast<int>(ended.size() + liveness.lost_count()) >= o.streams; };
  const bool written = sink_loop(o, health, drain, finished, [&] { results->wait_for_data(std::chrono::milliseconds(50)); },
                                 [&] { return results->matched(); });
  // After a failed write no summary.json claims a complete run; the files keep their complete lines.
  const bool closed = written && folders.close(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  log_received(*results);
  if (preview) log_received(preview->reader());
  health.report(closed ? msg::ComponentState::FINISHED : msg::ComponentState::FAILED);
  return sink_exit_code(finished(), closed, gate, liveness);
}

// The flight metadata of the source's input, read here rather than sent over DDS: the frame
// size and rate come from the video itself, as in `uavmot process`.
geo::ChainGround read_ground(SinkOptions& o, bool fps_given) {
  auto video = source::open_frame_source({.path = o.metadata});
  const source::SourceInfo& info = video->info();
  if (!fps_given) o.fps = info.fps;
  geo::ChainGround ground(geo::read_flight_metadata(o.metadata, info.size, o.fps, static_cast<int>(info.frame_count)));
  if (ground.flight().empty()) {
    spdlog::warn("--metadata '{}': no KLV metadata; no tracks.geojson", o.metadata);
    return ground;
  }
  const auto& m = ground.flight().summary;
  spdlog::info("KLV metadata of '{}': {} packets ({}), {} of {} frames have ground geometry; {}x{} at {:.3f} fps", o.metadata,
               m.packets, geo::metadata_standard(ground.flight()), m.frames_with_geometry, ground.flight().frames.size(),
               info.size.width, info.size.height, o.fps);
  const auto klv_gsd = ground.median_gsd_m(info.frame_count);
  if (o.gsd_m <= 0 && klv_gsd) {
    o.gsd_m = *klv_gsd;
    o.gsd_source = "klv";
    spdlog::info("GSD {:.3f} m/px from KLV metadata ({} packets, {})", o.gsd_m, m.packets, geo::metadata_standard(ground.flight()));
  }
  return ground;
}

int sink_main(int argc, char** argv) {
  dds::NodeOptions node;
  SinkOptions o;
  return run_app(argc, argv, "sink", "write the chain's results to files (motion, segmentation, tracks -> tracks.txt ...)", [&](CLI::App& app) {
    app.add_option("--out", o.out_dir, "output folder (one sub-folder per stream when --streams > 1)")->required();
    app.add_option("--gsd", o.gsd_m, "ground sampling distance, m/px: adds metric columns")->check(uavmot::positive_finite());
    auto* fps_option = app.add_option("--fps", o.fps, "frame rate, for speeds (with --metadata: default the video's)")
                           ->check(uavmot::positive_finite())
                           ->capture_default_str();
    auto* streams_option =
        app.add_option("--streams", o.streams, "write up to this many streams (the first valid ids that arrive); exit after they ended")
            ->check(uavmot::positive_finite())
            ->capture_default_str();
    // Comma-separated too, and "" for none: a launch profile passes its ids as one variable
    // (bringup/ground.yaml's stream_ids), which may be empty.
    app.add_option("--stream-id", o.stream_ids,
                   "write only this stream id (repeat, or separate by commas, for several; sets --streams; \"\": none); "
                   "default: the first ids that arrive")
        ->delimiter(',')
        ->check([](const std::string& id) { return id.empty() ? std::string() : stream_id_problem(id); });
    app.add_option("--idle-timeout", o.idle_timeout_s, "fail if nothing arrives for this long once started (s, 0 = wait forever)");
    app.add_option("--stream-timeout", o.stream_timeout_s,
                   "give up a stream (a UAV) that sent nothing for this long: the others go on, exit 1 at the end (s, 0 = wait "
                   "forever)")
        ->check(uavmot::non_negative_finite());
    dds::add_upstream_timeout_option(app, o.upstream_timeout_s);
    app.add_flag("--resume", o.resume,
                 "continue the unfinished run in --out after a crash or restart: keep its files (cut to whole frames) and "
                 "skip the frames they hold when they come again; refused for a finished run (summary.json)");
    app.add_flag("--downlink", o.downlink,
                 "read uavmot/downlink/results, what an air -> ground link carries (no features.csv, clusters.txt)");
    app.add_option("--preview-dir", o.preview_dir, "with --downlink: save the link's JPEG previews here");
    app.add_option("--metadata", o.metadata,
                   "the source's input video (MPEG-TS with KLV, from its first frame): adds tracks.geojson, lat,lon columns and "
                   "its GSD when --gsd is not given");
    dds::add_node_options(app, node);
    // fps_option, streams_option by value: locals of this set-up function, which returns before the run.
    return [&, fps_option, streams_option]() -> int {
      dds::finalize(node, "sink");
      o.stream_ids.erase(std::remove(o.stream_ids.begin(), o.stream_ids.end(), std::string()), o.stream_ids.end());
      if (!o.stream_ids.empty()) {
        const auto ids = static_cast<int>(std::set<std::string>(o.stream_ids.begin(), o.stream_ids.end()).size());
        if (streams_option->count() > 0 && o.streams != ids) {
          throw InputError(fmt::format("--streams {} but {} distinct --stream-id", o.streams, ids));
        }
        o.streams = ids;
      }
      if (!o.preview_dir.empty() && !o.downlink) throw InputError("--preview-dir needs --downlink");
      if (o.gsd_m > 0) o.gsd_source = "flag";
      std::optional<geo::ChainGround> ground;
      if (!o.metadata.empty()) {
        if (o.streams != 1) throw InputError("--metadata describes one stream; it cannot be used with --streams " + std::to_string(o.streams));
        ground = read_ground(o, fps_option->count() > 0);
        o.ground = &*ground;
      }
      install_shutdown_handler();
      dds::Participant participant(node.dds);
      return o.downlink ? run_downlink_sink(participant, o) : run_chain_sink(participant, o);
    };
  });
}

}  // namespace
}  // namespace uavmot

int main(int argc, char** argv) { return uavmot::sink_main(argc, argv); }
