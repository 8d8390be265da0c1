// Seeds for the segmentation_state fuzz target: saved states of a segmenter before any frame and after
// frames with a moving car (its cluster windows), written as tests/fuzz/corpus/segmentation_state/<name>.
//   cmake --build build --target fuzz_make_segmentation_state_corpus && build/fuzz/fuzz_make_segmentation_state_corpus tests/fuzz/corpus/segmentation_state
#include <cstdio>
#include <fstream>
#include <string>

#include <opencv2/core.hpp>

#include "uavmot/segmentation/segmenter.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s OUT_DIR\n", argv[0]);
    return 2;
  }
  const std::string dir = argv[1];
  uavmot::SceneInfo scene;
  scene.gsd_m = 0.3;
  scene.fps = 25.0;
  uavmot::segmentation::Segmenter segmenter(uavmot::segmentation::SegmentationOptions{}, scene);
  auto save = [&](const std::string& name) {
    const auto bytes = segmenter.save_state();
    std::ofstream(dir + "/" + name, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()),
                                                             static_cast<std::streamsize>(bytes.size()));
    std::printf("%s: %zu bytes\n", name.c_str(), bytes.size());
  };
  save("fresh");
  cv::Mat ground(64, 96, CV_8UC1);
  cv::RNG rng(7);
  rng.fill(ground, cv::RNG::UNIFORM, 80, 120);
  for (int k = 1; k <= 3; ++k) {
    uavmot::Frame f;
    uavmot::MotionEstimate m;
    f.stream_id = m.stream_id = "seed";
    f.index = m.frame_index = k;
    f.image = ground.clone();
    f.image(cv::Rect(30 + k, 30, 15, 6)).setTo(cv::Scalar(200));  // a car, 1 px/frame
    m.quality.valid = true;
    for (int i = 0; i < 6; ++i) {
      uavmot::TrackedFeature t;
      t.id = static_cast<uint64_t>(i + 1);
      t.position = {32.0 + k + 2.0 * i, 31.0 + (i % 2) * 3.0};
      t.velocity = {1.0, 0.0};
      t.moving = true;
      m.features.push_back(t);
    }
    segmenter.process(f, m);
    if (k == 1) save("after_1_frame");
    if (k == 3) save("after_3_frames");
  }
  return 0;
}
