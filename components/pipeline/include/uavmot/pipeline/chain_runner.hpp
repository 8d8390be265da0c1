#pragma once
// Runs the chain over a frame source, sequentially or pipelined, and hands every frame's result
// to the caller in frame order:
//
//   threads 1: decode, motion, segmentation, tracking of each frame one after another on the
//              calling thread (OpenCV's pool set to 1: one core).
//   threads 2: three stages overlap, joined by bounded in-order queues:
//                decode thread -> motion thread (frame k+1) -> calling thread (segmentation +
//                tracking of frame k, then `consume`)
//              The decode thread also builds the frame's LK pyramid (Chain::prepare_motion, no
//              state). Each stage owns its state and sees every frame in order, so the results
//              are the same bytes as threads 1 (tested: pipelined_chain_test). OpenCV's pool is
//              set to 2 (opencv_threads): it splits the motion thread's LK over the points.
//
// An exception in any stage reaches the caller after the frames before it were consumed; an
// exception in `consume` (or `stop()` turning true) stops the other stages, which are joined
// before run_chain returns or throws.

#include <cstdint>
#include <functional>
#include <memory>

#include "uavmot/pipeline/chain.hpp"
#include "uavmot/source/frame_source.hpp"

namespace uavmot::pipeline {

struct ChainRunOptions {
  int threads = 2;          // 1 = sequential, 2 = pipelined (above)
  size_t queue_depth = 3;   // frames waiting between two stages (bounds memory: 4K gray is 8 MB)
  int opencv_threads = 0;   // cv::setNumThreads during the run; 0 = `threads` (restored after)
  std::function<bool()> stop;  // asked before each frame by every stage (thread-safe!); true ends the run early (Ctrl-C)
};

using FrameConsumer = std::function<void(const Frame& frame, const ChainOutput& output)>;

// Returns the number of frames consumed.
int64_t run_chain(std::unique_ptr<source::FrameSource> frames, Chain& chain, const ChainRunOptions& options,
                  const FrameConsumer& consume);

}  // namespace uavmot::pipeline
