// view-annotate-frame: runs the in-process chain on a sequence up to one frame and saves that frame,
// annotated and cropped, as a PNG (the picture in docs/view.md). Without --crop it picks the
// window with the most confirmed tracks, so the picture shows the layers on several vehicles.
//
//   view-annotate-frame runs/paper --frame 120 --size 320x200 --scale 3 --out docs/images/annotated_paper.png

#include <cstdio>

#include <opencv2/imgcodecs.hpp>
#include <spdlog/spdlog.h>

#include "uavmot/core/app.hpp"
#include "uavmot/core/error.hpp"
#include "uavmot/core/logging.hpp"
#include "uavmot/pipeline/chain.hpp"
#include "uavmot/source/frame_source.hpp"
#include "uavmot/view/overlay.hpp"

namespace uavmot {
namespace {

// The window of `size` (frame px, inside the frame) whose area holds the most confirmed track centres.
cv::Rect busiest_window(const TrackList& tracks, cv::Size frame, cv::Size size) {
  cv::Rect best(0, 0, std::min(size.width, frame.width), std::min(size.height, frame.height));
  int best_count = -1;
  for (int y = 0; y + best.height <= frame.height; y += 8) {
    for (int x = 0; x + best.width <= frame.width; x += 8) {
      int count = 0;
      for (const auto& t : tracks.tracks) {
        // Whole box inside with a margin for the label.
        const double margin = 0.6 * std::max(t.box.length, t.box.width) + 4;
        if (t.state == TrackState::Confirmed && t.box.cx - margin >= x && t.box.cx + margin < x + best.width &&
            t.box.cy - margin - 12 >= y && t.box.cy + margin < y + best.height) {
          ++count;
        }
      }
      if (count > best_count) {
        best_count = count;
        best.x = x;
        best.y = y;
      }
    }
  }
  return best;
}

int annotate_main(int argc, char** argv) {
  source::FrameSourceOptions input;
  std::string out_file, crop_text, size_text = "320x200";
  int64_t frame_index = 100;
  view::OverlayOptions overlay;
  return run_app(argc, argv, "view-annotate-frame", "save one annotated frame of a sequence as PNG", [&](CLI::App& app) {
    app.add_option("input", input.path, "video, image folder or MOTChallenge sequence")->required();
    app.add_option("--frame", frame_index, "frame to draw (1-based)")->check(uavmot::positive_finite())->capture_default_str();
    app.add_option("--out", out_file, "PNG file")->required();
    app.add_option("--crop", crop_text, "x,y,w,h in frame pixels (default: the busiest --size window)");
    app.add_option("--size", size_text, "WxH of the automatic crop")->capture_default_str();
    app.add_option("--scale", overlay.scale, "enlargement")->check(uavmot::finite_range(0.1, 8.0))->capture_default_str();
    app.add_flag("--stationary", overlay.stationary_features, "also draw stationary features");
    return [&]() -> int {
      init_logging("annotate", "info");
      input.max_frames = frame_index;
      auto frames = source::open_frame_source(input);
      pipeline::ChainOptions options;
      if (frames->info().gsd_m > 0) options.scene.gsd_m = frames->info().gsd_m;
      options.scene.fps = frames->info().fps;
      overlay.gsd_m = options.scene.gsd_m;
      overlay.fps = options.scene.fps;
      pipeline::Chain chain(options);
      Frame frame;
      pipeline::ChainOutput out;
      bool reached = false;
      while (frames->next(frame)) {
        out = chain.process(frame);
        reached = frame.index == frame_index;
      }
      if (!reached) throw InputError(input.path + " has fewer than " + std::to_string(frame_index) + " frames");
      cv::Rect crop;
      if (!crop_text.empty()) {
        if (std::sscanf(crop_text.c_str(), "%d,%d,%d,%d", &crop.x, &crop.y, &crop.width, &crop.height) != 4) {
          throw InputError("--crop: expected x,y,w,h, got '" + crop_text + "'");
        }
      } else {
        cv::Size size;
        if (std::sscanf(size_text.c_str(), "%dx%d", &size.width, &size.height) != 2) {
          throw InputError("--size: expected WxH, got '" + size_text + "'");
        }
        crop = busiest_window(out.tracks, frame.image.size(), size);
      }
      crop &= cv::Rect(0, 0, frame.image.cols, frame.image.rows);
      if (crop.empty()) throw InputError("--crop lies outside the frame");
      const cv::Mat annotated = view::draw_overlay(frame.image, &out.motion, &out.segmentation, &out.tracks, overlay);
      const double s = overlay.scale;
      const cv::Rect scaled(cv::Point(static_cast<int>(crop.x * s), static_cast<int>(crop.y * s)),
                            cv::Size(static_cast<int>(crop.width * s), static_cast<int>(crop.height * s)));
      const cv::Mat picture = annotated(scaled & cv::Rect(0, 0, annotated.cols, annotated.rows));
      if (!cv::imwrite(out_file, picture, {cv::IMWRITE_PNG_COMPRESSION, 9})) throw InputError("cannot write " + out_file);
      int confirmed = 0;
      for (const auto& t : out.tracks.tracks) confirmed += t.state == TrackState::Confirmed;
      spdlog::info("frame {}: crop {},{} {}x{} x{} -> {} ({} confirmed tracks in the frame)", frame_index, crop.x, crop.y,
                   crop.width, crop.height, s, out_file, confirmed);
      for (const auto& t : out.tracks.tracks) {
        if (t.state != TrackState::Confirmed || !crop.contains(cv::Point(static_cast<int>(t.box.cx), static_cast<int>(t.box.cy)))) continue;
        spdlog::info("  track {} at ({:.1f}, {:.1f}) {:.1f} x {:.1f} px, {:.0f} deg, {}", t.id, t.box.cx, t.box.cy, t.box.length,
                     t.box.width, t.box.angle_deg, view::format_speed(t.velocity, overlay.gsd_m, overlay.fps));
      }
      return kExitOk;
    };
  });
}

}  // namespace
}  // namespace uavmot

int main(int argc, char** argv) { return uavmot::annotate_main(argc, argv); }
