// uavmot-sink: subscribes to motion, segmentation and tracks and writes the same files as
// `uavmot process` (tracks.txt, tracks_obb.csv, homographies.txt, features.csv, clusters.txt,
// regions.txt, summary.json) through the same writer, so lossless runs are byte-identical.
// With --downlink it reads the compact topics that cross an air -> ground link instead
// (uavmot/downlink/*: no features or clusters, float32 boxes; docs/deployment.md), and with
// --preview-dir it also saves the link's JPEG previews (uavmot/downlink/preview) there.
// With several streams, each gets a folder of its own under --out.

#include <filesystem>
#include <fstream>
#include <map>
#include <memory>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "downlinkPubSubTypes.h"
#include "framePubSubTypes.h"
#include "motionPubSubTypes.h"
#include "segmentationPubSubTypes.h"
#include "tracksPubSubTypes.h"
#include "uavmot/core/app.hpp"
#include "uavmot/core/error.hpp"
#include "uavmot/core/result_files.hpp"
#include "uavmot/core/shutdown.hpp"
#include "uavmot/dds/chain_convert.hpp"
#include "uavmot/dds/downlink_convert.hpp"
#include "uavmot/dds/health_reporter.hpp"
#include "uavmot/dds/node_options.hpp"
#include "uavmot/dds/node_support.hpp"

namespace uavmot {
namespace {

struct SinkOptions {
  std::string out_dir;
  double gsd_m = 0.0, fps = 25.0, idle_timeout_s = 0.0;
  int streams = 1;
  bool downlink = false;
  std::string preview_dir;  // downlink: save the JPEG previews here
};

// Saves every JPEG preview that arrives as PREVIEW_DIR/STREAM_FRAME.jpg.
class PreviewSaver {
 public:
  PreviewSaver(dds::Participant& participant, const std::string& dir)
      : dir_(dir), reader_(participant.make_reader<msg::FramePubSubType>(dds::kDownlinkPreviewTopic, dds::TopicClass::Preview)) {
    std::filesystem::create_directories(dir_);
  }
  bool pump() {
    msg::Frame sample;
    bool any = false;
    while (reader_->take(sample)) {
      any = true;
      if (sample.encoding() != msg::Encoding::JPEG || sample.data().empty()) continue;
      const std::string name = fmt::format("{}/{}_{:06d}.jpg", dir_, sample.stream_id().to_string(), sample.frame_index());
      std::ofstream(name, std::ios::binary).write(reinterpret_cast<const char*>(sample.data().data()),
                                                  static_cast<std::streamsize>(sample.data().size()));
      ++images_;
    }
    return any;
  }
  dds::TopicReader<msg::FramePubSubType>& reader() { return *reader_; }
  uint64_t images() const { return images_; }

 private:
  std::string dir_;
  std::unique_ptr<dds::TopicReader<msg::FramePubSubType>> reader_;
  uint64_t images_ = 0;
};

struct StreamFiles {
  std::unique_ptr<ResultFilesWriter> writer;
  bool motion_ended = false, segmentation_ended = false, tracks_ended = false;
  // Last frame written per topic (downlink): a writer's history sent again after the link was
  // lost and found (transient-local downlink topics) repeats frames already written.
  int64_t last_motion = 0, last_segmentation = 0, last_tracks = 0;
  bool done() const { return motion_ended && segmentation_ended && tracks_ended; }
};

// Reads the three topics (full or downlink types) until every expected stream ended on all three.
template <class MotionPub, class SegmentationPub, class TracksPub>
int run_sink(dds::Participant& participant, const SinkOptions& o, dds::TopicClass topic_class, const char* motion_topic,
             const char* segmentation_topic, const char* tracks_topic) {
  auto motion = participant.make_reader<MotionPub>(motion_topic, topic_class);
  auto segmentation = participant.make_reader<SegmentationPub>(segmentation_topic, topic_class);
  auto tracks = participant.make_reader<TracksPub>(tracks_topic, topic_class);
  dds::HealthReporter health(participant, "sink", "*");
  health.watch(*motion);
  health.watch(*segmentation);
  health.watch(*tracks);
  std::unique_ptr<PreviewSaver> preview;
  if (!o.preview_dir.empty()) {
    preview = std::make_unique<PreviewSaver>(participant, o.preview_dir);
    health.watch(preview->reader());
  }
  dds::RejectLog rejects;
  std::map<std::string, StreamFiles> files;
  const auto start = std::chrono::steady_clock::now();
  auto last_sample = start;
  bool started = false;

  auto files_for = [&](const std::string& stream) -> StreamFiles& {
    auto [it, fresh] = files.try_emplace(stream);
    if (fresh) {
      ResultFilesOptions r;
      r.directory = o.streams > 1 ? (std::filesystem::path(o.out_dir) / stream).string() : o.out_dir;
      r.fps = o.fps;
      r.gsd_m = o.gsd_m;
      // The downlink carries neither features nor clusters: no empty files pretending otherwise.
      r.write_features = r.write_clusters = !o.downlink;
      it->second.writer = std::make_unique<ResultFilesWriter>(r);
      spdlog::info("stream '{}' -> {}", stream, r.directory);
    }
    return it->second;
  };
  auto finished = [&]() {
    int done = 0;
    for (const auto& [id, f] : files) done += f.done() ? 1 : 0;
    return done >= o.streams;
  };
  // Each topic comes from one writer, in frame order: write each as it arrives.
  auto drain = [&](auto& reader, auto write, auto mark_end, int64_t StreamFiles::*last) {
    typename std::remove_reference_t<decltype(*reader)>::Sample sample;
    bool any = false;
    while (reader->take(sample)) {
      any = true;
      StreamFiles& f = files_for(sample.stream_id().to_string());
      if (sample.end_of_stream()) {
        mark_end(f);
        continue;
      }
      std::string why;
      auto value = dds::from_msg(sample, why);
      if (!value) {
        health.invalid_sample();
        rejects.log(reader->topic(), why);
        continue;
      }
      // Deduplicate after validation: a malformed sample must not hide the valid one of its frame.
      if (value->frame_index <= f.*last) continue;  // already written
      f.*last = value->frame_index;
      write(f, *value);
    }
    return any;
  };

  while (!shutdown_requested() && !finished()) {
    bool any = drain(motion, [&](StreamFiles& f, const MotionEstimate& m) { f.writer->write_motion(m); health.frame_in(); },
                     [](StreamFiles& f) { f.motion_ended = true; }, &StreamFiles::last_motion);
    any |= drain(segmentation, [](StreamFiles& f, const SegmentationResult& s) { f.writer->write_segmentation(s); },
                 [](StreamFiles& f) { f.segmentation_ended = true; }, &StreamFiles::last_segmentation);
    any |= drain(tracks, [&](StreamFiles& f, const TrackList& t) {
                   f.writer->write_tracks(t);
                   health.frame_out(t.frame_index, 0.0, dds::latency_ms_since(t.capture_time_ns));
                 },
                 [](StreamFiles& f) { f.tracks_ended = true; }, &StreamFiles::last_tracks);
    if (preview) preview->pump();
    health.tick();
    const auto now = std::chrono::steady_clock::now();
    if (any) {
      last_sample = now;
      started = true;
    } else {
      tracks->wait_for_data(std::chrono::milliseconds(50));
      if (started && o.idle_timeout_s > 0 && now - last_sample > std::chrono::duration<double>(o.idle_timeout_s)) {
        spdlog::error("nothing arrived for {} s; closing the files with what was received", o.idle_timeout_s);
        break;
      }
    }
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  for (auto& [id, f] : files) {
    RunSummary summary;
    summary.input = "dds:" + id;
    summary.wall_time_s = seconds;
    const int64_t frames = f.writer->frames_written();
    f.writer->close(summary);
    spdlog::info("stream '{}': {} frames written", id, frames);
  }
  auto received = [](const auto& r) { spdlog::info("{}: {} samples, {} bytes received", r.topic(), r.samples_taken(), r.bytes_taken()); };
  received(*motion);
  received(*segmentation);
  received(*tracks);
  if (preview) received(preview->reader());
  health.report(msg::ComponentState::FINISHED);
  return finished() ? kExitOk : kExitFailure;
}

int sink_main(int argc, char** argv) {
  dds::NodeOptions node;
  SinkOptions o;
  return run_app(argc, argv, "sink", "write the chain's results to files (motion, segmentation, tracks -> tracks.txt ...)", [&](CLI::App& app) {
    app.add_option("--out", o.out_dir, "output folder (one sub-folder per stream when --streams > 1)")->required();
    app.add_option("--gsd", o.gsd_m, "ground sampling distance, m/px: adds metric columns")->check(CLI::PositiveNumber);
    app.add_option("--fps", o.fps, "frame rate, for speeds")->check(CLI::PositiveNumber)->capture_default_str();
    app.add_option("--streams", o.streams, "exit after this many streams ended")->check(CLI::PositiveNumber)->capture_default_str();
    app.add_option("--idle-timeout", o.idle_timeout_s, "fail if nothing arrives for this long once started (s, 0 = wait forever)");
    app.add_flag("--downlink", o.downlink,
                 "read the compact uavmot/downlink/* topics of an air -> ground link (no features.csv, clusters.txt)");
    app.add_option("--preview-dir", o.preview_dir, "with --downlink: save the link's JPEG previews here");
    dds::add_node_options(app, node);
    return [&]() -> int {
      dds::finalize(node, "sink");
      if (!o.preview_dir.empty() && !o.downlink) throw InputError("--preview-dir needs --downlink");
      install_shutdown_handler();
      dds::Participant participant(node.dds);
      if (o.downlink) {
        return run_sink<msg::MotionSummaryPubSubType, msg::RegionListPubSubType, msg::CompactTrackListPubSubType>(
            participant, o, dds::TopicClass::Downlink, dds::kDownlinkMotionTopic, dds::kDownlinkRegionsTopic, dds::kDownlinkTracksTopic);
      }
      return run_sink<msg::MotionEstimatePubSubType, msg::SegmentationPubSubType, msg::TrackListPubSubType>(
          participant, o, dds::TopicClass::Chain, dds::kMotionTopic, dds::kSegmentationTopic, dds::kTracksTopic);
    };
  });
}

}  // namespace
}  // namespace uavmot

int main(int argc, char** argv) { return uavmot::sink_main(argc, argv); }
