#include "uavmot/view/live_view.hpp"

#include <algorithm>
#include <chrono>
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
#include "uavmot/core/error.hpp"
#include "uavmot/core/shutdown.hpp"
#include "uavmot/dds/chain_convert.hpp"
#include "uavmot/dds/frame_convert.hpp"
#include "uavmot/dds/health_reporter.hpp"
#include "uavmot/dds/node_support.hpp"
#include "uavmot/view/frame_joiner.hpp"
#include "uavmot/view/video_sink.hpp"

namespace uavmot::view {
namespace {

const char* const kWindowName = "uavmot view";

}  // namespace

int run_live_view(LiveViewOptions o) {
  const char* display = std::getenv("DISPLAY");
  const bool has_display = display != nullptr && *display != '\0';
  if (o.window && !has_display) {
    if (o.out_file.empty()) throw InputError("--window: no display ($DISPLAY is not set); pass --out FILE.mp4");
    spdlog::warn("--window: no display ($DISPLAY is not set); writing {} only", o.out_file);
    o.window = false;
  }
  if (!o.window && o.out_file.empty()) {
    throw InputError(has_display ? "nothing to show into: pass --window or --out FILE.mp4"
                                 : "no display ($DISPLAY is not set): pass --out FILE.mp4");
  }
  std::unique_ptr<VideoSink> video;
  if (!o.out_file.empty()) video = std::make_unique<VideoSink>(VideoSinkOptions{o.out_file, o.overlay.fps, o.fourcc});
  if (o.window) cv::namedWindow(kWindowName, cv::WINDOW_AUTOSIZE);

  dds::Participant participant(o.node.dds);
  auto frames = participant.make_reader<msg::FramePubSubType>(dds::kFramesTopic, dds::TopicClass::Frames);
  auto motion = participant.make_reader<msg::MotionEstimatePubSubType>(dds::kMotionTopic, dds::TopicClass::Chain);
  auto segmentation = participant.make_reader<msg::SegmentationPubSubType>(dds::kSegmentationTopic, dds::TopicClass::Chain);
  auto tracks = participant.make_reader<msg::TrackListPubSubType>(dds::kTracksTopic, dds::TopicClass::Chain);
  dds::HealthReporter health(participant, "view", o.stream.empty() ? "*" : o.stream);
  dds::RejectLog rejects;
  FrameJoiner joiner(o.max_lag);
  std::string stream = o.stream;
  bool frames_ended = false, tracks_ended = false, user_closed = false;
  int64_t drawn = 0;
  double busy_ms = 0.0;  // drawing + encoding + showing
  auto last_sample = std::chrono::steady_clock::now();
  std::optional<std::chrono::steady_clock::time_point> frames_ended_at;
  spdlog::info("{}, {}, {}, {} -> {} ({})", dds::kFramesTopic, dds::kMotionTopic, dds::kSegmentationTopic, dds::kTracksTopic,
               o.window ? (video ? "window + " + o.out_file : std::string("window")) : o.out_file, o.node.mode);

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
  auto show = [&](std::vector<JoinedFrame> ready) {
    for (auto& j : ready) {
      const auto t0 = std::chrono::steady_clock::now();
      const cv::Mat annotated = draw_overlay(j.frame.image, j.motion ? &*j.motion : nullptr,
                                                   j.segmentation ? &*j.segmentation : nullptr, j.tracks ? &*j.tracks : nullptr,
                                                   o.overlay);
      if (!j.tracks) spdlog::debug("frame {} drawn without its tracks", j.frame.index);
      if (video) video->write(annotated);
      if (o.window) {
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

  auto take_all = [&]() {
    bool any = take_frames();
    any |= drain(motion, [&](MotionEstimate m) { joiner.add_motion(std::move(m)); }, [] {});
    any |= drain(segmentation, [&](SegmentationResult s) { joiner.add_segmentation(std::move(s)); }, [] {});
    any |= drain(tracks, [&](TrackList t) { joiner.add_tracks(std::move(t)); }, [&] { tracks_ended = true; });
    return any;
  };

  while (!shutdown_requested() && !user_closed) {
    const bool any = take_all();
    show(joiner.pop_ready());
    health.set_queue_depth(static_cast<uint32_t>(joiner.pending()));
    health.tick();
    const auto now = std::chrono::steady_clock::now();
    if (any) last_sample = now;
    // The tracks' end-of-stream comes last through the chain; without it (a chain that is not
    // running, or live-mode loss) give the last results `--linger` seconds after the frames ended.
    if (frames_ended && !frames_ended_at) frames_ended_at = now;
    if (frames_ended && (tracks_ended || now - *frames_ended_at > std::chrono::duration<double>(o.linger_s))) break;
    if (o.idle_timeout_s > 0 && drawn > 0 && now - last_sample > std::chrono::duration<double>(o.idle_timeout_s)) {
      spdlog::warn("nothing arrived for {} s; stopping", o.idle_timeout_s);
      break;
    }
    if (!any) {
      if (o.window) {
        if (const int key = cv::waitKey(10); key == 'q' || key == 27) user_closed = true;
      } else {
        tracks->wait_for_data(std::chrono::milliseconds(10));
      }
    }
  }
  // Stopped (`uavmot launch` stops the view once the sink has finished): results that arrived but
  // were not taken yet still join their frames. Then whatever is buffered is drawn, so the video
  // has every frame that arrived.
  if (!user_closed) take_all();
  show(joiner.flush());
  if (video) {
    video->close();
    spdlog::info("{} frames -> {} ({:.1f} ms per frame to draw and encode)", video->frames_written(), video->path(),
                 busy_ms / std::max<int64_t>(drawn, 1));
  }
  if (joiner.released_incomplete() > 0) {
    spdlog::info("{} of {} frames drawn before their tracks arrived", joiner.released_incomplete(), drawn);
  }
  if (o.window) cv::destroyAllWindows();
  health.report(msg::ComponentState::FINISHED);
  return 0;
}

}  // namespace uavmot::view
