#pragma once
// uavmot-view's process: subscribes to frames, motion, segmentation and tracks, joins them by
// frame (FrameJoiner) and draws them like the paper's Fig. 6 (draw_overlay), in a window when a
// display exists, otherwise into an mp4 (VideoSink). Live mode by default: it never holds the
// chain back.

#include <string>

#include "uavmot/dds/node_options.hpp"
#include "uavmot/view/overlay.hpp"

namespace uavmot::view {

struct LiveViewOptions {
  dds::NodeOptions node;     // finalized
  std::string out_file;      // mp4; empty: none
  std::string fourcc = "avc1";
  std::string stream;        // draw only this stream; empty: the first one seen
  bool window = false;       // needs $DISPLAY; without one, only out_file is written
  OverlayOptions overlay;
  int max_lag = 10;          // frames a frame waits for its tracks
  double linger_s = 2.0;     // after the frames ended, wait this long for the last results
  double idle_timeout_s = 0.0;  // stop if nothing arrives for this long once started; 0: never
};

// Runs until the streams' results ended, the user closed the window or a shutdown was requested;
// returns the exit code. Throws InputError when there is nothing to draw into.
int run_live_view(LiveViewOptions options);

}  // namespace uavmot::view
