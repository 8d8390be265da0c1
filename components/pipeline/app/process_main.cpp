// uavmot-process: the whole chain in one process, no DDS. Reads a video, image folder or
// MOTChallenge sequence and writes tracks.txt, tracks_obb.csv, homographies.txt, features.csv,
// clusters.txt, regions.txt and summary.json; with flight metadata (KLV in MPEG-TS) also
// tracks.geojson and lat,lon columns (docs/geo.md). Given a recording (REC.mcap or --from-recording),
// re-runs only tracking on its motion estimates and segmentation results.

#include <chrono>
#include <filesystem>
#include <memory>

#include <spdlog/spdlog.h>

#include "uavmot/core/app.hpp"
#include "uavmot/core/error.hpp"
#include "uavmot/core/logging.hpp"
#include "uavmot/core/result_files.hpp"
#include "uavmot/core/scene_info.hpp"
#include "uavmot/core/shutdown.hpp"
#include "uavmot/geo/chain_ground.hpp"
#include "uavmot/geo/track_map.hpp"
#include "uavmot/pipeline/chain.hpp"
#include "uavmot/pipeline/chain_runner.hpp"
#include "uavmot/pipeline/progress.hpp"
#include "uavmot/source/frame_source.hpp"
#include "uavmot/view/overlay.hpp"
#include "uavmot/view/video_sink.hpp"
#include "input_scene.hpp"
#include "process_recording.hpp"

namespace uavmot {
namespace {

int process_main(int argc, char** argv) {
  source::FrameSourceOptions input;
  std::string out_dir, config_file, method, video_file, log_level = "info";
  double gsd_m = 0.0, fps = 0.0;
  bool quiet = false, from_recording = false;
  int threads = 2, opencv_threads = 0;

  return run_app(argc, argv, "process", "run the whole chain in one process and write tracks", [&](CLI::App& app) {
    app.add_option("input", input.path, "video file, image folder, MOTChallenge sequence folder or recording (.mcap)")
        ->required();
    app.add_flag("--from-recording", from_recording,
                 "the input is an MCAP recording: re-run tracking on its motion and segmentation (default for *.mcap)");
    app.add_option("--out", out_dir, "output folder")->required();
    app.add_option("--config", config_file, "chain configuration YAML (sections scene, motion, segmentation, tracking)");
    app.add_option("--segmentation", method, segmentation_method_choices() + " (default from config: fusion)")
        ->check(CLI::IsMember(segmentation_method_names()));
    app.add_option("--gsd", gsd_m, "ground sampling distance, m/px (default: seqinfo.ini gsd, else KLV metadata, else config, else 0.35)")
        ->check(uavmot::positive_finite());
    app.add_option("--fps", fps, "frame rate (default: the input's; a CLIF folder's from its ../pos GPS times)")->check(uavmot::positive_finite());
    app.add_option("--start", input.start_frame, "first input frame (1-based)")->check(uavmot::positive_finite());
    app.add_option("--count", input.max_frames, "number of frames (0 = all)")->check(uavmot::non_negative_finite());
    app.add_option("--stream-id", input.stream_id, "stream id written into every result")->capture_default_str();
    app.add_option("--video", video_file, "also write the annotated video (paper Fig. 6) to this mp4 file");
    app.add_option("--threads", threads,
                   "1: one frame after another on one thread; 2: decoding, motion of frame k+1 and segmentation + "
                   "tracking of frame k overlap on their own threads (same results, byte for byte)")
        ->check(CLI::Range(1, 2))
        ->capture_default_str();
    app.add_option("--opencv-threads", opencv_threads, "OpenCV's own pool during the run (default: --threads)")
        ->check(CLI::Range(1, 64));
    app.add_flag("--quiet", quiet, "no progress line");
    app.add_option("--log-level", log_level)->check(CLI::IsMember({"trace", "debug", "info", "warn", "error", "off"}));

    return [&]() -> int {
      init_logging("process", log_level);
      install_shutdown_handler();
      pipeline::ChainOptions options = config_file.empty() ? pipeline::ChainOptions{} : pipeline::load_chain_options(config_file);
      if (!method.empty()) options.segmentation.method = parse_segmentation_method(method);
      if (from_recording || std::filesystem::path(input.path).extension() == ".mcap") {
        if (gsd_m > 0) options.scene.gsd_m = gsd_m;
        if (fps > 0) options.scene.fps = fps;
        return pipeline::process_recording(input.path, out_dir, options);
      }
      // A CLIF folder's frame rate is in its POS records' GPS times, not in the images.
      const auto clif_pos = pipeline::read_clif_pos_for(input.path);
      if (fps <= 0 && clif_pos && clif_pos->fps()) input.fps_override = *clif_pos->fps();
      auto frames = source::open_frame_source(input);
      const source::SourceInfo info = frames->info();  // a copy: run_chain takes the source
      options.scene.fps = fps > 0 ? fps : info.fps;
      if (input.fps_override > 0) spdlog::info("frame rate {:.3f} fps from the CLIF POS GPS times", info.fps);
      // The flight metadata of an MPEG-TS: geometry per frame, numbered as the chain numbers them.
      const int input_frames = info.frame_count > 0 ? static_cast<int>(info.frame_count + input.start_frame - 1) : 0;
      const geo::ChainGround ground(geo::read_flight_metadata(input.path, info.size, options.scene.fps, input_frames), input.start_frame);
      if (!ground.flight().empty()) {
        const auto& m = ground.flight().summary;
        spdlog::info("KLV metadata: {} packets ({}), {} bad checksums, {} undecodable; {} of {} frames have ground geometry",
                     m.packets, geo::metadata_standard(ground.flight()), m.bad_checksum, m.undecodable, m.frames_with_geometry,
                     ground.flight().frames.size());
      }
      pipeline::GsdCandidates gsd;
      gsd.flag_m = gsd_m;
      gsd.seqinfo_m = info.gsd_m;
      gsd.flight = &ground.flight();
      gsd.klv_m = ground.median_gsd_m(info.frame_count);
      gsd.config_m = pipeline::config_gsd_m(config_file, options.scene.gsd_m);
      gsd.default_m = SceneInfo{}.gsd_m;
      gsd.clif_pos = clif_pos.has_value();
      const pipeline::GsdChoice gsd_choice = pipeline::choose_gsd(gsd);
      options.scene.gsd_m = gsd_choice.gsd_m;
      spdlog::info("{} '{}': {}x{}, {} frames at {:.2f} fps; GSD {:.4g} m/px ({}); segmentation {}", info.kind, input.path,
                   info.size.width, info.size.height, info.frame_count, options.scene.fps, options.scene.gsd_m,
                   gsd_choice.source, to_string(options.segmentation.method));

      pipeline::Chain chain(options);
      ResultFilesOptions files;
      files.directory = out_dir;
      files.fps = options.scene.fps;
      files.gsd_m = options.scene.gsd_m;
      geo::TrackMapRecorder track_map;
      ResultFilesWriter writer(files, ground.has_ground_mapping() ? ground.pixel_to_lat_lon() : PixelToLatLon{});
      std::unique_ptr<view::VideoSink> video;
      view::OverlayOptions overlay;
      overlay.gsd_m = options.scene.gsd_m;
      overlay.fps = options.scene.fps;
      if (!video_file.empty()) video = std::make_unique<view::VideoSink>(view::VideoSinkOptions{video_file, options.scene.fps});
      pipeline::Progress progress("process", info.frame_count, !quiet);
      const auto start = std::chrono::steady_clock::now();
      int exit_code = kExitOk;
      int64_t done = 0;
      pipeline::ChainRunOptions run;
      run.threads = threads;
      run.opencv_threads = opencv_threads;
      run.stop = [] { return shutdown_requested(); };
      try {
        pipeline::run_chain(std::move(frames), chain, run, [&](const Frame& frame, const pipeline::ChainOutput& out) {
          writer.write_motion(out.motion);
          writer.write_segmentation(out.segmentation);
          writer.write_tracks(out.tracks);
          track_map.add(out.tracks);
          if (video) video->write(view::draw_overlay(frame.image, &out.motion, &out.segmentation, &out.tracks, overlay));
          progress.update(++done);
        });
      } catch (const InputError& e) {
        // Everything processed so far is written below; the input itself is broken.
        progress.finish();
        spdlog::error("{}", e.what());
        exit_code = kExitBadInput;
      }
      progress.finish();
      RunSummary summary;
      summary.input = input.path;
      summary.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      const pipeline::StageTimes& times = chain.stage_times();
      const double per_frame_ms = 1e3 / static_cast<double>(std::max<int64_t>(1, times.frames));
      summary.stage_mean_ms = {{"motion", times.motion_s * per_frame_ms},
                               {"segmentation", times.segmentation_s * per_frame_ms},
                               {"tracking", times.tracking_s * per_frame_ms}};
      summary.gsd_source = gsd_choice.source;
      if (!ground.flight().empty()) summary.metadata = ground.summary();
      writer.close(summary);
      if (ground.has_ground_mapping()) {
        const auto counts = ground.write_geojson(std::filesystem::path(out_dir) / "tracks.geojson", track_map, options.scene.fps);
        spdlog::info("tracks.geojson: {} tracks on the map ({} points without ground geometry, {} tracks with fewer than two points left out)",
                     counts.features, counts.skipped_points, counts.skipped_tracks);
      }
      if (video) video->close();
      spdlog::info("{} frames in {:.1f} s ({:.1f} fps) -> {}; per frame: motion {:.1f} ms, segmentation {:.1f} ms, tracking {:.1f} ms",
                   done, summary.wall_time_s, done / std::max(summary.wall_time_s, 1e-9), out_dir,
                   summary.stage_mean_ms["motion"], summary.stage_mean_ms["segmentation"], summary.stage_mean_ms["tracking"]);
      // Boxes sit half a shadow off in sunlight; say whether and by how much they were moved back.
      if (const pipeline::ShadowSummary shadow = chain.shadow_summary(); shadow.frames > 0) {
        const cv::Vec2d m = shadow.median_px * options.scene.gsd_m;
        spdlog::info("vehicle shadows taken out of the boxes in {} of {} frames: median offset ({:+.2f}, {:+.2f}) px, ({:+.2f}, {:+.2f}) m",
                     shadow.frames, times.frames, shadow.median_px[0], shadow.median_px[1], m[0], m[1]);
      } else {
        spdlog::info("no vehicle shadows taken out of the boxes (too few bright vehicles, or none casting one consistent shadow)");
      }
      // Whether the flight showed 3-D structure, and how much of it the motion layer held still.
      spdlog::info("{}", motion::describe_structure(chain.motion_stats()));
      return exit_code;
    };
  });
}

}  // namespace
}  // namespace uavmot

int main(int argc, char** argv) { return uavmot::process_main(argc, argv); }
