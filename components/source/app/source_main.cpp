// uavmot-source: publishes the frames of a video, image folder or MOTChallenge sequence on
// uavmot/frames, paced at a rate or, in lossless mode, as fast as the slowest subscriber takes them.

#include <algorithm>
#include <atomic>
#include <chrono>
#include <filesystem>
#include <thread>

#include <spdlog/spdlog.h>

#include "framePubSubTypes.h"
#include "uavmot/core/app.hpp"
#include "uavmot/core/error.hpp"
#include "uavmot/core/shutdown.hpp"
#include "uavmot/dds/frame_convert.hpp"
#include "uavmot/dds/health_reporter.hpp"
#include "uavmot/dds/node_options.hpp"
#include "uavmot/dds/node_support.hpp"
#include "published_position.hpp"
#include "uavmot/source/frame_prefetcher.hpp"
#include "uavmot/source/frame_source.hpp"

namespace uavmot {
namespace {

int source_main(int argc, char** argv) {
  source::FrameSourceOptions input;
  dds::NodeOptions node;
  std::string color = "gray";
  double rate_hz = 0.0;
  bool native_rate = false;
  double wait_timeout_s = 30.0;
  int64_t first_index = 1;  // frame index on the wire of the first frame published
  std::string state_dir;

  return run_app(argc, argv, "source", "publish frames of a video, image folder or MOTChallenge sequence", [&](CLI::App& app) {
    app.add_option("input", input.path, "video file, image folder or MOTChallenge sequence folder")->required();
    app.add_option("--stream-id", input.stream_id, "key of this stream (one per UAV)")->capture_default_str();
    app.add_option("--start", input.start_frame, "first input frame (1-based)")->check(uavmot::positive_finite())->capture_default_str();
    app.add_option("--first-index", first_index,
                   "number the published frames from this index (a run that continues an earlier one, e.g. with --start: "
                   "a restored tracker skips the frames its state already holds)")
        ->check(uavmot::positive_finite())
        ->capture_default_str();
    app.add_option("--state-dir", state_dir,
                   "save the index of every frame published here; on start, continue from the last one saved (sent "
                   "again: it may not have arrived; readers skip what they have). For a respawned source");
    app.add_option("--count", input.max_frames, "number of frames (0 = all)")->check(uavmot::non_negative_finite())->capture_default_str();
    app.add_flag("--loop", input.loop, "start again after the last frame");
    app.add_option("--color", color, "gray or color")->check(CLI::IsMember({"gray", "color"}))->capture_default_str();
    app.add_flag("--skip-corrupt", input.skip_corrupt, "skip undecodable images with a warning instead of failing");
    auto* rate = app.add_option("--rate", rate_hz, "publish at this rate (Hz); frames are timestamped at it")->check(uavmot::positive_finite());
    app.add_flag("--native", native_rate, "publish at the input's own frame rate (default in live mode)")->excludes(rate);
    app.add_option("--wait-timeout", wait_timeout_s, "seconds to wait for subscribers")->capture_default_str();
    node.wait_subscribers = 1;
    dds::add_node_options(app, node);

    return [&]() -> int {
      dds::finalize(node, "source");
      install_shutdown_handler();
      input.color = source::parse_color_mode(color);
      input.fps_override = rate_hz;
      const std::string position_file = state_dir.empty() ? "" : source::published_position_file(state_dir, input.stream_id);
      if (!state_dir.empty()) {
        std::filesystem::create_directories(state_dir);
        if (const auto last = source::load_published_position(position_file); last && *last >= first_index) {
          if (input.loop) {
            spdlog::warn("--loop: not continuing from frame {} ('{}'), starting again", *last, position_file);
          } else {
            const int64_t done = *last - first_index;  // frames fully behind us
            input.start_frame += done;
            if (input.max_frames > 0) input.max_frames -= done;
            first_index = *last;
            spdlog::info("continuing from frame {} (input frame {}), the last one published before ('{}')", *last,
                         input.start_frame, position_file);
          }
        }
      }
      auto frames = source::open_frame_source(input);
      const auto& info = frames->info();
      spdlog::info("{} '{}': {}x{}, {} frames, {:.3f} fps", info.kind, input.path, info.size.width, info.size.height,
                   info.frame_count, info.fps);

      dds::Participant participant(node.dds);
      auto writer = participant.make_writer<msg::FramePubSubType>(dds::kFramesTopic, dds::TopicClass::Frames);
      dds::HealthReporter health(participant, "source", input.stream_id);
      health.watch(*writer);
      const bool lossless = node.dds.mode == dds::DeliveryMode::Lossless;
      const bool paced = rate_hz > 0.0 || native_rate || !lossless;
      const auto period = std::chrono::nanoseconds(static_cast<int64_t>(1e9 / info.fps));

      // Live: a camera does not wait. Frame k is due at start + (k - 1) period; once frame k + 1 is
      // due, frame k is too late: the reading thread passes over it undecoded, or, if it was
      // decoded already and a newer frame is waiting, it is dropped below. Either way it counts as
      // dropped on the health topic.
      // The reading thread decodes the first frames while subscribers are awaited.
      const bool skip_late = !lossless;
      using Clock = std::chrono::steady_clock;
      std::atomic<Clock::rep> start_ticks{0};  // when the stream started; 0 before
      auto late_for = [&](int64_t index) {
        const Clock::rep ticks = start_ticks.load();
        return ticks != 0 && Clock::now() >= Clock::time_point(Clock::duration(ticks)) + period * index;
      };
      source::FramePrefetcher ahead(std::move(frames), 3, [&](int64_t index) { return skip_late && late_for(index); });

      const int wait_subscribers = node.wait_subscribers;
      if (lossless) writer->set_required_readers(wait_subscribers);
      if (wait_subscribers > 0) {
        spdlog::info("waiting for {} subscriber(s) on {}", wait_subscribers, dds::kFramesTopic);
        if (!writer->wait_for_matched(wait_subscribers, std::chrono::milliseconds(static_cast<int64_t>(wait_timeout_s * 1000)))) {
          if (shutdown_requested()) return kExitOk;
          spdlog::error("no subscriber within {} s: {} of {} matched on {}", wait_timeout_s, writer->matched(), wait_subscribers,
                        dds::kFramesTopic);
          return kExitFailure;
        }
      }

      Frame frame;
      // Pacing and capture times count from the first frame published; only the index on the wire moves.
      const int64_t index_offset = first_index - 1;
      int64_t published = 0, dropped_late = 0, reported_undecoded = 0;
      // Capture times go on the wire on the wall clock (stream start + (index - 1) / rate), so every
      // component can tell its latency; the results never depend on them.
      int64_t stream_start_ns = dds::wall_clock_ns();
      int exit_code = kExitOk;
      bool undelivered = false;  // lossless: a frame its readers did not take; the stream has not ended
      auto start = Clock::now();
      // Live, with subscribers to wait for: a reader that the writer has matched may not be listening
      // yet (segmentation lost frame 1 in about one hd start in six; the last reader can take some
      // 300 ms). So the first frame waits for every reader's acknowledgement, and the camera clock
      // starts after that: frame k > 1 is due (k - 1) periods after the acknowledgement, and its
      // capture time is the stream start + (k - 1) / rate where the stream start is moved by the
      // wait; the first frame keeps the capture time it was sent with.
      const bool handshake = !lossless && wait_subscribers > 0;
      if (!handshake) start_ticks = start.time_since_epoch().count();
      auto count_undecoded = [&] {
        const int64_t undecoded = ahead.skipped_undecoded();
        for (; reported_undecoded < undecoded; ++reported_undecoded) {
          health.frame_in();
          health.dropped();
        }
      };
      try {
        while (!shutdown_requested() && ahead.next(frame)) {
          count_undecoded();
          if (skip_late && late_for(frame.index) && ahead.next_ready()) {  // a newer frame is there
            ++dropped_late;
            health.frame_in();
            health.dropped();
            continue;
          }
          if (paced) std::this_thread::sleep_until(start + period * (frame.index - 1));
          const auto t0 = std::chrono::steady_clock::now();
          frame.capture_time_ns += stream_start_ns;
          auto sample = dds::to_msg(frame);
          sample.frame_index(frame.index + index_offset);
          const bool ok = lossless ? writer->write_reliably(sample) : writer->write(sample);
          if (handshake && published == 0) {
            const auto sent = Clock::now();
            if (!writer->flush(std::chrono::seconds(2))) spdlog::warn("frame {} not acknowledged by every reader", frame.index);
            // The camera clock starts now: the frames after the first are due from here on.
            const auto waited = Clock::now() - sent;
            start += waited;
            stream_start_ns += std::chrono::duration_cast<std::chrono::nanoseconds>(waited).count();
            start_ticks = start.time_since_epoch().count();
          }
          if (!ok) {
            if (lossless) {
              spdlog::error("frame {} was not delivered; stopping so nothing is silently lost", frame.index);
              exit_code = kExitFailure;
              undelivered = true;
              break;
            }
            health.dropped();
          }
          ++published;
          if (!position_file.empty() && !source::save_published_position(position_file, frame.index + index_offset)) {
            spdlog::warn("cannot write '{}'", position_file);
          }
          health.frame_in();
          // Paced, the capture time is when the frame was due: latency shows how far the source lags behind.
          health.frame_out(frame.index + index_offset, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count(),
                           paced ? dds::latency_ms_since(frame.capture_time_ns) : 0.0);
          health.set_bytes_out(writer->bytes_sent());
          health.tick();
          if (published % 100 == 0) spdlog::info("published {} frames", published);
        }
        count_undecoded();
      } catch (const InputError& e) {
        // Frames already published stay published; the stream is closed properly below.
        spdlog::error("{}", e.what());
        exit_code = kExitBadInput;
      }
      const int64_t skipped_late = dropped_late + ahead.skipped_undecoded();
      // No end of stream after an undelivered frame: the readers would finish a stream that a
      // respawned source (--state-dir) continues from its last delivered frame.
      if (!undelivered) {
        auto eos = dds::end_of_stream_frame(input.stream_id, std::max(frame.index, ahead.last_index()) + index_offset);
        writer->write_reliably(eos, dds::end_of_stream_patience(node.dds.mode));
        writer->flush(dds::end_of_stream_patience(node.dds.mode));
      }
      health.report(exit_code == kExitOk ? msg::ComponentState::FINISHED : msg::ComponentState::FAILED);
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      spdlog::info("published {} frames in {:.2f} s ({:.1f} fps){}{}", published, seconds, published / std::max(seconds, 1e-9),
                   skipped_late ? fmt::format(", skipped {} it was late for", skipped_late) : "",
                   ahead.skipped_corrupt() ? fmt::format(", skipped {} corrupt", ahead.skipped_corrupt()) : "");
      return exit_code;
    };
  });
}

}  // namespace
}  // namespace uavmot

int main(int argc, char** argv) { return uavmot::source_main(argc, argv); }
