// Fuzz target: arbitrary bytes as a saved motion estimator state (MotionEstimator::restore_state,
// what a respawned uavmot-motion reads from its --state-dir). The header's payload size and checksum
// are set to match the bytes first, so the fuzzer reaches the payload's checks instead of stopping
// at the checksum. Bad input must end in uavmot::InputError, never a crash or another exception; a
// state the estimator accepts must also carry it through the next frames.

#include <cstddef>
#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

#include "fuzz_targets.hpp"
#include "state_envelope.hpp"
#include "uavmot/core/error.hpp"
#include "uavmot/motion/motion_estimator.hpp"

namespace uavmot::fuzz {
namespace {

// A small textured frame that moves by `k` px: what the restored state is carried through.
Frame frame(int k) {
  Frame f;
  f.stream_id = "fuzz";
  f.index = k;
  cv::Mat image(48, 64, CV_8UC1);
  for (int y = 0; y < image.rows; ++y) {
    for (int x = 0; x < image.cols; ++x) image.at<uint8_t>(y, x) = static_cast<uint8_t>(((x + k) * 37 ^ y * 91) & 0xFF);
  }
  f.image = image;
  return f;
}

}  // namespace

int motion_state(const uint8_t* data, size_t size) {
  std::vector<uint8_t> bytes(data, data + size);
  match_envelope(bytes);
  motion::MotionEstimator estimator(motion::MotionOptions{});
  try {
    estimator.restore_state(bytes);
  } catch (const InputError&) {
    return 0;
  }
  const int64_t next = estimator.last_frame_index() + 1;
  for (int64_t k = next; k < next + 2; ++k) estimator.process(frame(static_cast<int>(k & 0xFF)));
  return 0;
}

}  // namespace uavmot::fuzz
