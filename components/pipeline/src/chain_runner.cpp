#include "uavmot/pipeline/chain_runner.hpp"

#include <pthread.h>

#include <thread>

#include <opencv2/core/utility.hpp>

#include "stage_queue.hpp"
#include "uavmot/core/error.hpp"
#include "uavmot/source/frame_prefetcher.hpp"

namespace uavmot::pipeline {
namespace {

bool stopped(const ChainRunOptions& o) { return o.stop && o.stop(); }

int64_t run_sequential(source::FrameSource& frames, Chain& chain, const ChainRunOptions& options, const FrameConsumer& consume) {
  int64_t done = 0;
  Frame frame;
  while (!stopped(options) && frames.next(frame)) {
    consume(frame, chain.process(frame));
    ++done;
  }
  return done;
}

struct MotionDone {
  Frame frame;
  MotionEstimate motion;
};

int64_t run_pipelined(std::unique_ptr<source::FrameSource> frames, Chain& chain, const ChainRunOptions& options,
                      const FrameConsumer& consume) {
  source::FramePrefetcher decoded(std::move(frames), options.queue_depth);
  StageQueue<MotionDone> moved(options.queue_depth);
  std::thread motion_thread([&] {
    pthread_setname_np(pthread_self(), "uavmot-motion");  // for top -H and perf
    try {
      Frame frame;
      while (!stopped(options) && decoded.next(frame)) {
        MotionEstimate motion = chain.estimate_motion(frame);
        if (!moved.push({std::move(frame), std::move(motion)})) break;  // the consumer stopped
      }
      moved.close();
    } catch (...) {
      moved.close(std::current_exception());
    }
  });
  int64_t done = 0;
  try {
    MotionDone item;
    while (!stopped(options) && moved.pop(item)) {
      consume(item.frame, chain.segment_and_track(item.frame, std::move(item.motion)));
      ++done;
    }
  } catch (...) {
    moved.cancel();
    motion_thread.join();
    throw;
  }
  moved.cancel();
  motion_thread.join();
  return done;
}

// OpenCV's pool size for the run, the previous size restored after (also on an exception).
class OpenCvThreads {
 public:
  explicit OpenCvThreads(int threads) : previous_(cv::getNumThreads()) { cv::setNumThreads(threads); }
  ~OpenCvThreads() { cv::setNumThreads(previous_); }
  OpenCvThreads(const OpenCvThreads&) = delete;
  OpenCvThreads& operator=(const OpenCvThreads&) = delete;

 private:
  int previous_;
};

}  // namespace

int64_t run_chain(std::unique_ptr<source::FrameSource> frames, Chain& chain, const ChainRunOptions& options,
                  const FrameConsumer& consume) {
  if (options.threads != 1 && options.threads != 2) {
    throw InvalidArgument("chain threads must be 1 or 2, not " + std::to_string(options.threads));
  }
  const OpenCvThreads opencv_threads(options.opencv_threads > 0 ? options.opencv_threads : options.threads);
  if (options.threads == 1) return run_sequential(*frames, chain, options, consume);
  return run_pipelined(std::move(frames), chain, options, consume);
}

}  // namespace uavmot::pipeline
