// uavmot-view: the operator's view (uavmot/view/live_view.hpp): frames, motion, segmentation
// and tracks over DDS, drawn like the paper's Fig. 6 in a window or into an mp4. This file only
// reads the command line.

#include <limits>

#include "uavmot/core/app.hpp"
#include "uavmot/core/shutdown.hpp"
#include "uavmot/dds/node_options.hpp"
#include "uavmot/view/live_view.hpp"

namespace uavmot {
namespace {

int view_main(int argc, char** argv) {
  view::LiveViewOptions o;
  o.node.mode = "live";  // a viewer must not slow the chain down
  CLI::Option* lag_option = nullptr;  // these outlive the setup lambda: the body reads them
  CLI::Option* linger_option = nullptr;
  return run_app(argc, argv, "view", "draw frames, features, regions and tracks (window or mp4)", [&](CLI::App& app) {
    app.add_option("--out", o.out_file, "write the annotated video to this mp4 file");
    app.add_option("--fourcc", o.fourcc, "avc1 (H.264, plays in browsers; default) or mp4v (MPEG-4 Part 2)")
        ->check(CLI::IsMember({"mp4v", "avc1"}))
        ->capture_default_str();
    app.add_flag("--window", o.window, "show a window (needs $DISPLAY)");
    app.add_option("--gsd", o.overlay.gsd_m, "ground sampling distance, m/px: speeds in km/h (else px/frame)")
        ->check(uavmot::positive_finite());
    app.add_option("--fps", o.overlay.fps, "frame rate: time label, km/h and the mp4's rate")
        ->check(uavmot::positive_finite())->capture_default_str();
    app.add_option("--stream-id", o.stream, "draw only this stream (default: the first one seen)");
    app.add_option("--scale", o.overlay.scale, "output size / frame size")->check(uavmot::finite_range(0.05, 8.0))->capture_default_str();
    app.add_option("--vector-scale", o.overlay.vector_scale, "feature velocity arrows span this many frames")
        ->check(uavmot::positive_finite())->capture_default_str();
    app.add_flag("--stationary", o.overlay.stationary_features, "also draw stationary features (small red dots)");
    lag_option = app.add_option("--max-lag", o.max_lag, "draw a frame without its tracks once it is this many frames old (live; lossless: 250)")
                     ->check(CLI::Range(0, 1000))
                     ->capture_default_str();
    linger_option = app.add_option("--linger", o.linger_s,
                                   "after the frames ended, wait this long for the last results (s; live mode; "
                                   "lossless waits for the tracks' end of stream)")
                        ->check(uavmot::non_negative_finite())
                        ->capture_default_str();
    app.add_option("--idle-timeout", o.idle_timeout_s, "stop if nothing arrives for this long once started (s, 0 = never)")
        ->check(uavmot::non_negative_finite());
    dds::add_node_options(app, o.node);
    return [&]() -> int {
      dds::finalize(o.node, "view");
      // Lossless: every result comes, so wait for it (the chain's backpressure bounds the lag).
      if (o.node.dds.mode == dds::DeliveryMode::Lossless && lag_option->count() == 0) o.max_lag = 250;
      // Lossless: the last tracks come however far tracking runs behind; --idle-timeout still applies.
      if (o.node.dds.mode == dds::DeliveryMode::Lossless && linger_option->count() == 0) {
        o.linger_s = std::numeric_limits<double>::infinity();
      }
      install_shutdown_handler();
      return view::run_live_view(o);
    };
  });
}

}  // namespace
}  // namespace uavmot

int main(int argc, char** argv) { return uavmot::view_main(argc, argv); }
