// uavmot-view: the operator's view. Subscribes to frames, motion, segmentation and tracks, joins
// them by frame and draws them like the paper's Fig. 6, in a window when a display exists
// (--window), otherwise into an mp4 (--out). Live mode by default: it never holds the chain back.

#include <cstdlib>
#include <limits>
#include <memory>
#include <optional>

#include <opencv2/highgui.hpp>
#include <spdlog/spdlog.h>

#include "framePubSubTypes.h"
#include "motionPubSubTypes.h"
#include "segmentationPubSubTypes.h"
#include "tracksPubSubTypes.h"
#include "uavmot/core/app.hpp"
#include "uavmot/core/error.hpp"
#include "uavmot/core/shutdown.hpp"
#include "uavmot/dds/chain_convert.hpp"
#include "uavmot/dds/frame_convert.hpp"
#include "uavmot/dds/health_reporter.hpp"
#include "uavmot/dds/node_options.hpp"
#include "uavmot/dds/node_support.hpp"
#include "uavmot/view/frame_joiner.hpp"
#include "uavmot/view/overlay.hpp"
#include "uavmot/view/video_sink.hpp"

namespace uavmot {
namespace {

const char* const kWindowName = "uavmot view";

int view_main(int argc, char** argv) {
  dds::NodeOptions node;
  node.mode = "live";  // a viewer must not slow the chain down
  std::string out_file, stream_filter, fourcc = "avc1";
  view::OverlayOptions overlay;
  bool window = false;
  int max_lag = 10;
  CLI::Option* lag_option = nullptr;  // these outlive the setup lambda: the body reads them
  CLI::Option* linger_option = nullptr;
  double linger_s = 2.0, idle_timeout_s = 0.0;
  return run_app(argc, argv, "view", "draw frames, features, regions and tracks (window or mp4)", [&](CLI::App& app) {
    app.add_option("--out", out_file, "write the annotated video to this mp4 file");
    app.add_option("--fourcc", fourcc, "avc1 (H.264, plays in browsers; default) or mp4v (MPEG-4 Part 2)")
        ->check(CLI::IsMember({"mp4v", "avc1"}))
        ->capture_default_str();
    app.add_flag("--window", window, "show a window (needs $DISPLAY)");
    app.add_option("--gsd", overlay.gsd_m, "ground sampling distance, m/px: speeds in km/h (else px/frame)")
        ->check(CLI::PositiveNumber);
    app.add_option("--fps", overlay.fps, "frame rate: time label, km/h and the mp4's rate")
        ->check(CLI::PositiveNumber)->capture_default_str();
    app.add_option("--stream-id", stream_filter, "draw only this stream (default: the first one seen)");
    app.add_option("--scale", overlay.scale, "output size / frame size")->check(CLI::Range(0.05, 8.0))->capture_default_str();
    app.add_option("--vector-scale", overlay.vector_scale, "feature velocity arrows span this many frames")
        ->check(CLI::PositiveNumber)->capture_default_str();
    app.add_flag("--stationary", overlay.stationary_features, "also draw stationary features (small red dots)");
    lag_option = app.add_option("--max-lag", max_lag, "draw a frame without its tracks once it is this many frames old (live; lossless: 250)")
                     ->check(CLI::Range(0, 1000))
                     ->capture_default_str();
    linger_option = app.add_option("--linger", linger_s,
                                   "after the frames ended, wait this long for the last results (s; live mode; "
                                   "lossless waits for the tracks' end of stream)")
                        ->check(CLI::NonNegativeNumber)
                        ->capture_default_str();
    app.add_option("--idle-timeout", idle_timeout_s, "stop if nothing arrives for this long once started (s, 0 = never)")
        ->check(CLI::NonNegativeNumber);
    dds::add_node_options(app, node);
    return [&]() -> int {
      dds::finalize(node, "view");
      // Lossless: every result comes, so wait for it (the chain's backpressure bounds the lag).
      if (node.dds.mode == dds::DeliveryMode::Lossless && lag_option->count() == 0) max_lag = 250;
      // Lossless: the last tracks come however far tracking runs behind; --idle-timeout still applies.
      if (node.dds.mode == dds::DeliveryMode::Lossless && linger_option->count() == 0) {
        linger_s = std::numeric_limits<double>::infinity();
      }
      install_shutdown_handler();
      const char* display = std::getenv("DISPLAY");
      const bool has_display = display != nullptr && *display != '\0';
      if (window && !has_display) {
        if (out_file.empty()) throw InputError("--window: no display ($DISPLAY is not set); pass --out FILE.mp4");
        spdlog::warn("--window: no display ($DISPLAY is not set); writing {} only", out_file);
        window = false;
      }
      if (!window && out_file.empty()) {
        throw InputError(has_display ? "nothing to show into: pass --window or --out FILE.mp4"
                                     : "no display ($DISPLAY is not set): pass --out FILE.mp4");
      }
      std::unique_ptr<view::VideoSink> video;
      if (!out_file.empty()) video = std::make_unique<view::VideoSink>(view::VideoSinkOptions{out_file, overlay.fps, fourcc});
      if (window) cv::namedWindow(kWindowName, cv::WINDOW_AUTOSIZE);

      dds::Participant participant(node.dds);
      auto frames = participant.make_reader<msg::FramePubSubType>(dds::kFramesTopic, dds::TopicClass::Frames);
      auto motion = participant.make_reader<msg::MotionEstimatePubSubType>(dds::kMotionTopic, dds::TopicClass::Chain);
      auto segmentation = participant.make_reader<msg::SegmentationPubSubType>(dds::kSegmentationTopic, dds::TopicClass::Chain);
      auto tracks = participant.make_reader<msg::TrackListPubSubType>(dds::kTracksTopic, dds::TopicClass::Chain);
      dds::HealthReporter health(participant, "view", stream_filter.empty() ? "*" : stream_filter);
      dds::RejectLog rejects;
      view::FrameJoiner joiner(max_lag);
      std::string stream = stream_filter;
      bool frames_ended = false, tracks_ended = false, user_closed = false;
      int64_t drawn = 0;
      double busy_ms = 0.0;  // drawing + encoding + showing
      auto last_sample = std::chrono::steady_clock::now();
      std::optional<std::chrono::steady_clock::time_point> frames_ended_at;
      spdlog::info("{}, {}, {}, {} -> {} ({})", dds::kFramesTopic, dds::kMotionTopic, dds::kSegmentationTopic, dds::kTracksTopic,
                   window ? (video ? "window + " + out_file : std::string("window")) : out_file, node.mode);

      // Accepts a sample of the stream being drawn (the first one seen when no filter is given).
      auto ours = [&](const std::string& id) {
        if (stream.empty()) {
          stream = id;
          spdlog::info("drawing stream '{}'", stream);
        }
        return id == stream;
      };
      auto drain = [&](auto& reader, auto add, auto on_end) {
        typename std::remove_reference_t<decltype(*reader)>::Sample sample;
        bool any = false;
        while (reader->take(sample)) {
          any = true;
          if (!ours(sample.stream_id().to_string())) continue;
          if (sample.end_of_stream()) {
            on_end();
            continue;
          }
          std::string why;
          auto value = dds::from_msg(sample, why);
          if (!value) {
            health.invalid_sample();
            rejects.log(reader->topic(), why);
            continue;
          }
          add(std::move(*value));
        }
        return any;
      };
      auto take_frames = [&]() {
        return drain(frames, [&](Frame f) { health.frame_in(); joiner.add_frame(std::move(f)); }, [&] { frames_ended = true; });
      };
      auto show = [&](std::vector<view::JoinedFrame> ready) {
        for (auto& j : ready) {
          const auto t0 = std::chrono::steady_clock::now();
          const cv::Mat annotated = view::draw_overlay(j.frame.image, j.motion ? &*j.motion : nullptr,
                                                       j.segmentation ? &*j.segmentation : nullptr, j.tracks ? &*j.tracks : nullptr,
                                                       overlay);
          if (!j.tracks) spdlog::debug("frame {} drawn without its tracks", j.frame.index);
          if (video) video->write(annotated);
          if (window) {
            cv::imshow(kWindowName, annotated);
            const int key = cv::waitKey(1);
            if (key == 'q' || key == 27) user_closed = true;
          }
          ++drawn;
          const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
          busy_ms += ms;
          // Live readers keep only the newest frame: take what came while this one was drawn.
          take_frames();
          health.frame_out(j.frame.index, ms, dds::latency_ms_since(j.frame.capture_time_ns));
        }
      };

      while (!shutdown_requested() && !user_closed) {
        bool any = take_frames();
        any |= drain(motion, [&](MotionEstimate m) { joiner.add_motion(std::move(m)); }, [] {});
        any |= drain(segmentation, [&](SegmentationResult s) { joiner.add_segmentation(std::move(s)); }, [] {});
        any |= drain(tracks, [&](TrackList t) { joiner.add_tracks(std::move(t)); }, [&] { tracks_ended = true; });
        show(joiner.pop_ready());
        health.set_queue_depth(static_cast<uint32_t>(joiner.pending()));
        health.tick();
        const auto now = std::chrono::steady_clock::now();
        if (any) last_sample = now;
        // The tracks' end-of-stream comes last through the chain; without it (a chain that is not
        // running, or live-mode loss) give the last results `--linger` seconds after the frames ended.
        if (frames_ended && !frames_ended_at) frames_ended_at = now;
        if (frames_ended && (tracks_ended || now - *frames_ended_at > std::chrono::duration<double>(linger_s))) break;
        if (idle_timeout_s > 0 && drawn > 0 && now - last_sample > std::chrono::duration<double>(idle_timeout_s)) {
          spdlog::warn("nothing arrived for {} s; stopping", idle_timeout_s);
          break;
        }
        if (!any) {
          if (window) {
            if (const int key = cv::waitKey(10); key == 'q' || key == 27) user_closed = true;
          } else {
            tracks->wait_for_data(std::chrono::milliseconds(10));
          }
        }
      }
      // Whatever is still buffered is drawn, so the video has every frame that arrived.
      show(joiner.flush());
      if (video) {
        video->close();
        spdlog::info("{} frames -> {} ({:.1f} ms per frame to draw and encode)", video->frames_written(), video->path(),
                     busy_ms / std::max<int64_t>(drawn, 1));
      }
      if (joiner.released_incomplete() > 0) {
        spdlog::info("{} of {} frames drawn before their tracks arrived", joiner.released_incomplete(), drawn);
      }
      if (window) cv::destroyAllWindows();
      health.report(msg::ComponentState::FINISHED);
      return kExitOk;
    };
  });
}

}  // namespace
}  // namespace uavmot

int main(int argc, char** argv) { return uavmot::view_main(argc, argv); }
