#include "uavmot/pipeline/chain_runner.hpp"

#include <pthread.h>

#include <functional>
#include <thread>

#include <opencv2/core/utility.hpp>

#include "stage_queue.hpp"
#include "uavmot/core/error.hpp"

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

struct Decoded {
  Frame frame;
  motion::PreparedFrame prepared;
};

struct MotionDone {
  Frame frame;
  MotionEstimate motion;
};

// Runs `body` on a thread named `name` (top -H, perf); `failed` gets what it throws.
std::thread stage_thread(const char* name, std::function<void()> body, std::function<void(std::exception_ptr)> failed) {
  return std::thread([name, body = std::move(body), failed = std::move(failed)] {
    pthread_setname_np(pthread_self(), name);
    try {
      body();
    } catch (...) {
      failed(std::current_exception());
    }
  });
}

int64_t run_pipelined(std::unique_ptr<source::FrameSource> frames, Chain& chain, const ChainRunOptions& options,
                      const FrameConsumer& consume) {
  StageQueue<Decoded> decoded(options.queue_depth);
  StageQueue<MotionDone> moved(options.queue_depth);
  std::thread decode_thread = stage_thread(
      "uavmot-decode",
      [&] {
        Frame frame;
        while (!stopped(options) && frames->next(frame)) {
          motion::PreparedFrame prepared = chain.prepare_motion(frame);
          if (!decoded.push({std::move(frame), std::move(prepared)})) return;  // motion stopped
        }
        decoded.close();
      },
      [&](std::exception_ptr e) { decoded.close(e); });
  std::thread motion_thread = stage_thread(
      "uavmot-motion",
      [&] {
        Decoded item;
        while (!stopped(options) && decoded.pop(item)) {
          MotionEstimate motion = chain.estimate_motion(item.frame, std::move(item.prepared));
          if (!moved.push({std::move(item.frame), std::move(motion)})) break;  // the consumer stopped
        }
        decoded.cancel();
        moved.close();
      },
      [&](std::exception_ptr e) {
        decoded.cancel();
        moved.close(e);
      });
  // Whatever ends the run, the stages are stopped and joined before run_chain returns or throws.
  auto join = [&] {
    moved.cancel();
    motion_thread.join();  // it cancels `decoded` on its way out, which stops the decoder
    decode_thread.join();
  };
  int64_t done = 0;
  try {
    MotionDone item;
    while (!stopped(options) && moved.pop(item)) {
      consume(item.frame, chain.segment_and_track(item.frame, std::move(item.motion)));
      ++done;
    }
  } catch (...) {
    join();
    throw;
  }
  join();
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
