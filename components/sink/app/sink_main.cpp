// uavmot-sink: subscribes to motion, segmentation and tracks and writes the same files as
// `uavmot process` (tracks.txt, tracks_obb.csv, homographies.txt, features.csv, clusters.txt,
// regions.txt, summary.json) through the same writer, so lossless runs are byte-identical.
// With --downlink it reads what crosses an air -> ground link instead: uavmot/downlink/results,
// one compact sample per frame (no features or clusters; exact, docs/deployment.md), and
// with --preview-dir it also saves the link's JPEG previews (uavmot/downlink/preview) there.
// With several streams, each gets a folder of its own under --out.

#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
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

// The result files of every stream, one folder each when several are expected.
class ResultFolders {
 public:
  explicit ResultFolders(const SinkOptions& o) : o_(o) {}

  ResultFilesWriter& of(const std::string& stream) {
    auto [it, fresh] = writers_.try_emplace(stream);
    if (fresh) {
      ResultFilesOptions r;
      r.directory = o_.streams > 1 ? (std::filesystem::path(o_.out_dir) / stream).string() : o_.out_dir;
      r.fps = o_.fps;
      r.gsd_m = o_.gsd_m;
      // The downlink carries neither features nor clusters: no empty files pretending otherwise.
      r.write_features = r.write_clusters = !o_.downlink;
      it->second = std::make_unique<ResultFilesWriter>(r);
      spdlog::info("stream '{}' -> {}", stream, r.directory);
    }
    return *it->second;
  }
  void close(double seconds) {
    for (auto& [id, writer] : writers_) {
      RunSummary summary;
      summary.input = "dds:" + id;
      summary.wall_time_s = seconds;
      const int64_t frames = writer->frames_written();
      writer->close(summary);
      spdlog::info("stream '{}': {} frames written", id, frames);
    }
  }

 private:
  const SinkOptions& o_;
  std::map<std::string, std::unique_ptr<ResultFilesWriter>> writers_;
};

// Runs `drain` (true when it took anything) until `finished`, the idle timeout or shutdown.
template <class Drain, class Finished, class Wait>
void sink_loop(const SinkOptions& o, dds::HealthReporter& health, Drain drain, Finished finished, Wait wait) {
  auto last_sample = std::chrono::steady_clock::now();
  bool started = false;
  while (!shutdown_requested() && !finished()) {
    const bool any = drain();
    health.tick();
    const auto now = std::chrono::steady_clock::now();
    if (any) {
      last_sample = now;
      started = true;
    } else {
      wait();
      if (started && o.idle_timeout_s > 0 && now - last_sample > std::chrono::duration<double>(o.idle_timeout_s)) {
        spdlog::error("nothing arrived for {} s; closing the files with what was received", o.idle_timeout_s);
        break;
      }
    }
  }
}

auto log_received = [](const auto& r) { spdlog::info("{}: {} samples, {} bytes received", r.topic(), r.samples_taken(), r.bytes_taken()); };

// The full chain topics (one host): each comes from one writer, in frame order; written as they arrive.
int run_chain_sink(dds::Participant& participant, const SinkOptions& o) {
  auto motion = participant.make_reader<msg::MotionEstimatePubSubType>(dds::kMotionTopic, dds::TopicClass::Chain);
  auto segmentation = participant.make_reader<msg::SegmentationPubSubType>(dds::kSegmentationTopic, dds::TopicClass::Chain);
  auto tracks = participant.make_reader<msg::TrackListPubSubType>(dds::kTracksTopic, dds::TopicClass::Chain);
  dds::HealthReporter health(participant, "sink", "*");
  health.watch(*motion);
  health.watch(*segmentation);
  health.watch(*tracks);
  dds::RejectLog rejects;
  ResultFolders folders(o);
  std::map<std::string, std::set<std::string>> ended;  // per stream: the topics that ended
  std::map<std::pair<std::string, std::string>, int64_t> last_frame;  // per stream and topic
  const auto start = std::chrono::steady_clock::now();

  auto drain = [&](auto& reader, auto write) {
    typename std::remove_reference_t<decltype(*reader)>::Sample sample;
    bool any = false;
    while (reader->take(sample)) {
      any = true;
      const std::string stream = sample.stream_id().to_string();
      ResultFilesWriter& files = folders.of(stream);
      if (sample.end_of_stream()) {
        ended[stream].insert(reader->topic());
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
      int64_t& last = last_frame[{stream, reader->topic()}];
      if (value->frame_index <= last) continue;  // already written
      last = value->frame_index;
      write(files, *value);
    }
    return any;
  };
  auto finished = [&] {
    int done = 0;
    for (const auto& [id, topics] : ended) done += topics.size() >= 3 ? 1 : 0;
    return done >= o.streams;
  };
  sink_loop(o, health, [&] {
    bool any = drain(motion, [&](ResultFilesWriter& f, const MotionEstimate& m) { f.write_motion(m); health.frame_in(); });
    any |= drain(segmentation, [](ResultFilesWriter& f, const SegmentationResult& s) { f.write_segmentation(s); });
    any |= drain(tracks, [&](ResultFilesWriter& f, const TrackList& t) {
      f.write_tracks(t);
      health.frame_out(t.frame_index, 0.0, dds::latency_ms_since(t.capture_time_ns));
    });
    return any;
  }, finished, [&] { tracks->wait_for_data(std::chrono::milliseconds(50)); });
  folders.close(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  log_received(*motion);
  log_received(*segmentation);
  log_received(*tracks);
  health.report(msg::ComponentState::FINISHED);
  return finished() ? kExitOk : kExitFailure;
}

// The link (air -> ground): one sample per frame with what the UAV's chain produced of it.
int run_downlink_sink(dds::Participant& participant, const SinkOptions& o) {
  auto results = participant.make_reader<msg::FrameResultsPubSubType>(dds::kDownlinkResultsTopic, dds::TopicClass::Downlink);
  dds::HealthReporter health(participant, "sink", "*");
  health.watch(*results);
  std::unique_ptr<PreviewSaver> preview;
  if (!o.preview_dir.empty()) {
    preview = std::make_unique<PreviewSaver>(participant, o.preview_dir);
    health.watch(preview->reader());
  }
  dds::RejectLog rejects;
  ResultFolders folders(o);
  std::map<std::string, int64_t> last_frame;  // per stream
  std::set<std::string> ended;
  const auto start = std::chrono::steady_clock::now();

  auto drain = [&] {
    msg::FrameResults sample;
    bool any = false;
    while (results->take(sample)) {
      any = true;
      const std::string stream = sample.stream_id().to_string();
      ResultFilesWriter& files = folders.of(stream);
      if (sample.end_of_stream()) {
        ended.insert(stream);
        continue;
      }
      std::string why;
      auto parts = dds::from_msg(sample, why);
      if (!parts) {
        health.invalid_sample();
        rejects.log(results->topic(), why);
        continue;
      }
      // The writer's history, sent again after the link was lost and found (transient-local),
      // repeats frames already written.
      int64_t& last = last_frame[stream];
      if (sample.frame_index() <= last) continue;
      last = sample.frame_index();
      if (parts->motion) {
        files.write_motion(*parts->motion);
        health.frame_in();
      }
      if (parts->regions) files.write_printed_regions(sample.frame_index(), *parts->regions);
      if (parts->tracks) files.write_tracks(*parts->tracks);
      health.frame_out(sample.frame_index(), 0.0, dds::latency_ms_since(sample.capture_time_ns()));
    }
    if (preview) any |= preview->pump();
    return any;
  };
  auto finished = [&] { return static_cast<int>(ended.size()) >= o.streams; };
  sink_loop(o, health, drain, finished, [&] { results->wait_for_data(std::chrono::milliseconds(50)); });
  folders.close(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  log_received(*results);
  if (preview) log_received(preview->reader());
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
                 "read uavmot/downlink/results, what an air -> ground link carries (no features.csv, clusters.txt)");
    app.add_option("--preview-dir", o.preview_dir, "with --downlink: save the link's JPEG previews here");
    dds::add_node_options(app, node);
    return [&]() -> int {
      dds::finalize(node, "sink");
      if (!o.preview_dir.empty() && !o.downlink) throw InputError("--preview-dir needs --downlink");
      install_shutdown_handler();
      dds::Participant participant(node.dds);
      return o.downlink ? run_downlink_sink(participant, o) : run_chain_sink(participant, o);
    };
  });
}

}  // namespace
}  // namespace uavmot

int main(int argc, char** argv) { return uavmot::sink_main(argc, argv); }
