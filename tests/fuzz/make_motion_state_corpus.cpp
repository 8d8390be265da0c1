// Seeds for the motion_state fuzz target: saved states of a small moving scene (no frame yet, after
// one frame, after several), written as tests/fuzz/corpus/motion_state/<name>.
//   cmake --build build --target fuzz_make_motion_state_corpus && build/fuzz/fuzz_make_motion_state_corpus tests/fuzz/corpus/motion_state
#include <cstdio>
#include <fstream>
#include <string>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "uavmot/motion/motion_estimator.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s OUT_DIR\n", argv[0]);
    return 2;
  }
  const std::string dir = argv[1];
  cv::Mat ground(200, 200, CV_8UC1);
  cv::RNG rng(7);
  rng.fill(ground, cv::RNG::UNIFORM, 0, 255);
  cv::GaussianBlur(ground, ground, cv::Size(5, 5), 1.5);
  uavmot::motion::MotionEstimator estimator(uavmot::motion::MotionOptions{});
  auto save = [&](const std::string& name) {
    const auto bytes = estimator.save_state();
    std::ofstream(dir + "/" + name, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()),
                                                             static_cast<std::streamsize>(bytes.size()));
    std::printf("%s: %zu bytes\n", name.c_str(), bytes.size());
  };
  save("fresh");
  for (int k = 1; k <= 6; ++k) {
    uavmot::Frame f;
    f.stream_id = "seed";
    f.index = k;
    f.image = ground(cv::Rect(10 + 2 * k, 20 + k, 64, 48)).clone();
    cv::rectangle(f.image, cv::Rect(30 - 2 * k, 10, 8, 6), cv::Scalar(255), cv::FILLED);  // a moving patch
    estimator.process(f);
    if (k == 1) save("after_1_frame");
    if (k == 6) save("after_6_frames");
  }
  return 0;
}
