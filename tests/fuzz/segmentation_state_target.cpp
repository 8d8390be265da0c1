// Fuzz target: arbitrary bytes as a saved segmentation state (Segmenter::restore_state, what
// uavmot-segmentation reads from its --state-dir on start). The envelope's payload size and checksum
// are set to match the bytes first, so the fuzzer reaches the payload's checks. Bad input must end in
// uavmot::InputError, never a crash or another exception; a state the segmenter accepts is then used
// by the shift check of the next frame (its windows anywhere, of any size up to the format's limit).

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "fuzz_targets.hpp"
#include "state_envelope.hpp"
#include "uavmot/core/error.hpp"
#include "uavmot/segmentation/segmenter.hpp"

namespace uavmot::fuzz {
namespace {

// A textured 96 x 64 frame with a bright car at column `x`, and a motion estimate whose features on
// the car move 1 px/frame: a cluster whose regions the shift check compares with the previous windows.
struct Step {
  Frame frame;
  MotionEstimate motion;
};

Step step(const std::string& stream, int64_t index) {
  Step s;
  s.frame.stream_id = s.motion.stream_id = stream;
  s.frame.index = s.motion.frame_index = index;
  cv::Mat image(64, 96, CV_8UC1);
  for (int y = 0; y < image.rows; ++y) {
    for (int x = 0; x < image.cols; ++x) image.at<uint8_t>(y, x) = static_cast<uint8_t>(90 + ((x * 37 ^ y * 91) & 0x1F));
  }
  const int x = 30 + static_cast<int>(index & 0x0F);
  image(cv::Rect(x, 30, 15, 6)).setTo(cv::Scalar(200));
  s.frame.image = image;
  s.motion.quality.valid = true;
  for (int i = 0; i < 6; ++i) {
    TrackedFeature f;
    f.id = static_cast<uint64_t>(i + 1);
    f.position = {x + 2.0 + 2.0 * i, 31.0 + (i % 2) * 3.0};
    f.velocity = {1.0, 0.0};
    f.moving = true;
    s.motion.features.push_back(f);
  }
  return s;
}

}  // namespace

int segmentation_state(const uint8_t* data, size_t size) {
  std::vector<uint8_t> bytes(data, data + size);
  match_envelope(bytes);
  SceneInfo scene;
  scene.gsd_m = 0.3;
  scene.fps = 25.0;
  segmentation::Segmenter segmenter(segmentation::SegmentationOptions{}, scene);
  try {
    segmenter.restore_state(bytes);
  } catch (const InputError&) {
    return 0;
  }
  if (segmenter.save_state() != bytes) throw std::logic_error("an accepted segmentation state saves back to other bytes");
  // The next frames of the stream the state names, so that the shift check uses its windows.
  const int64_t next = segmenter.last_frame_index() + 1;
  for (int64_t k = next; k < next + 2; ++k) {
    const Step s = step(segmenter.last_stream_id(), k);
    segmenter.process(s.frame, s.motion);
  }
  return 0;
}

}  // namespace uavmot::fuzz
