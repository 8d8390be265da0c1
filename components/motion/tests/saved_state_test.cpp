// MotionEstimator::save_state / restore_state: an estimator restored from a state continues with
// the same bytes as the one that saved it; a bad state is refused with InputError and changes nothing.
#include <cstdio>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "test_support.hpp"
#include "uavmot/core/checksum.hpp"
#include "uavmot/core/error.hpp"

namespace uavmot::motion {
namespace {

// An estimate as bytes: every field, doubles bit for bit.
std::string serialised(const MotionEstimate& e) {
  std::string out;
  auto put = [&out](const auto& v) { out.append(reinterpret_cast<const char*>(&v), sizeof v); };
  out += e.stream_id;
  put(e.frame_index);
  put(e.capture_time_ns);
  put(e.image_width);
  put(e.image_height);
  for (double v : e.homography.val) put(v);
  put(e.quality.valid);
  put(e.quality.inliers);
  put(e.quality.residual_px);
  put(e.features.size());
  for (const auto& f : e.features) {
    put(f.id);
    put(f.position.x);
    put(f.position.y);
    put(f.velocity[0]);
    put(f.velocity[1]);
    put(f.velocity_sigma);
    put(f.age);
    put(f.moving);
  }
  return out;
}

testing::WarpedSequence moving_scene() {
  testing::WarpedSequence sequence(test::camera(4.0, 0.1, {640, 480}));
  sequence.set_patches(testing::scatter_patches(sequence, 10, 10, 5, 0.3, 1.5, 5));
  return sequence;
}

constexpr int kFrames = 24;

std::vector<std::string> uninterrupted(const testing::WarpedSequence& sequence) {
  std::vector<std::string> out;
  MotionEstimator estimator(MotionOptions{});
  for (int k = 1; k <= kFrames; ++k) out.push_back(serialised(estimator.process(test::make_frame(sequence.frame(k), k))));
  return out;
}

TEST(SavedState, RestoredEstimatorContinuesBitIdentically) {
  const auto sequence = moving_scene();
  const auto reference = uninterrupted(sequence);
  // Cut after the first frame (no tracks yet), early (short histories, classifiers in their
  // hysteresis) and late (full histories, moving features, the detector's back-off running).
  for (const int cut : {1, 3, 12, 20}) {
    SCOPED_TRACE("state saved after frame " + std::to_string(cut));
    MotionEstimator first(MotionOptions{});
    for (int k = 1; k <= cut; ++k) {
      ASSERT_EQ(serialised(first.process(test::make_frame(sequence.frame(k), k))), reference[static_cast<size_t>(k - 1)]);
    }
    const std::vector<uint8_t> state = first.save_state();
    MotionEstimator second(MotionOptions{});
    second.restore_state(state);
    EXPECT_EQ(second.last_frame_index(), cut);
    EXPECT_EQ(second.save_state(), state) << "saving a restored state gives the same bytes";
    int moving = 0;
    for (int k = cut + 1; k <= kFrames; ++k) {
      const MotionEstimate e = second.process(test::make_frame(sequence.frame(k), k));
      for (const auto& f : e.features) moving += f.moving;
      ASSERT_EQ(serialised(e), reference[static_cast<size_t>(k - 1)]) << "frame " << k;
    }
    EXPECT_GT(moving, 0) << "the comparison should cover moving features";
  }
}

TEST(SavedState, PreparedFramesContinueBitIdentically) {
  const auto sequence = moving_scene();
  const auto reference = uninterrupted(sequence);
  MotionEstimator first(MotionOptions{});
  for (int k = 1; k <= 10; ++k) first.process(test::make_frame(sequence.frame(k), k));
  MotionEstimator second(MotionOptions{});
  second.restore_state(first.save_state());
  for (int k = 11; k <= kFrames; ++k) {
    const Frame frame = test::make_frame(sequence.frame(k), k);
    ASSERT_EQ(serialised(second.process(frame, second.prepare(frame))), reference[static_cast<size_t>(k - 1)]) << k;
  }
}

TEST(SavedState, FreshEstimatorRoundTrips) {
  MotionEstimator fresh(MotionOptions{});
  const auto state = fresh.save_state();
  MotionEstimator other(MotionOptions{});
  other.restore_state(state);
  EXPECT_EQ(other.last_frame_index(), 0);
  EXPECT_EQ(other.save_state(), state);
}

// Every kind of damage is an InputError with a message, and leaves the estimator as it was.
TEST(SavedState, BadStatesAreRefusedAndChangeNothing) {
  const auto sequence = moving_scene();
  const auto reference = uninterrupted(sequence);
  MotionEstimator saver(MotionOptions{});
  for (int k = 1; k <= 12; ++k) saver.process(test::make_frame(sequence.frame(k), k));
  const std::vector<uint8_t> good = saver.save_state();
  ASSERT_GT(good.size(), 640u * 480u);

  std::vector<std::vector<uint8_t>> bad;
  bad.emplace_back();  // empty file
  for (size_t n : {size_t{3}, size_t{8}, size_t{12}, size_t{20}, size_t{27}, size_t{28}, size_t{29}, size_t{100},
                   good.size() / 2, good.size() - 1}) {
    bad.emplace_back(good.begin(), good.begin() + static_cast<long>(n));  // truncated
  }
  auto padded = good;
  padded.push_back(0);
  bad.push_back(padded);
  for (size_t at : {size_t{0}, size_t{9}, size_t{13}, size_t{21}, size_t{30}, size_t{200}, good.size() / 2, good.size() - 1}) {
    auto flipped = good;
    flipped[at] ^= 0x10;  // magic, version, size, checksum, payload
    bad.push_back(flipped);
  }
  for (const auto& bytes : bad) {
    MotionEstimator target(MotionOptions{});
    for (int k = 1; k <= 12; ++k) target.process(test::make_frame(sequence.frame(k), k));
    try {
      target.restore_state(bytes);
      ADD_FAILURE() << "a state of " << bytes.size() << " bytes was accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("motion estimator state"), std::string::npos) << e.what();
    }
    EXPECT_EQ(target.save_state(), good) << "a refused state must change nothing";
    EXPECT_EQ(serialised(target.process(test::make_frame(sequence.frame(13), 13))), reference[12]);
  }
}

TEST(SavedState, OtherOptionsAreRefused) {
  MotionEstimator saver(MotionOptions{});
  const auto state = saver.save_state();
  MotionOptions other;
  other.history_frames = 12;
  MotionEstimator target(other);
  try {
    target.restore_state(state);
    FAIL() << "a state of other options was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("other motion options"), std::string::npos) << e.what();
  }
}


// Damage that keeps the checksum valid (a state written wrongly, not torn): random bytes of the
// payload changed and the checksum recomputed. Each is refused with InputError or, if every check
// passes, the estimator carries on through the next frames without crashing.
TEST(SavedState, MutatedStatesWithAValidChecksumNeverCrash) {
  cv::Mat ground(200, 200, CV_8UC1);
  cv::RNG texture(7);
  texture.fill(ground, cv::RNG::UNIFORM, 0, 255);
  cv::GaussianBlur(ground, ground, cv::Size(5, 5), 1.5);
  auto small_frame = [&](int k) {
    return test::make_frame(ground(cv::Rect(10 + 2 * (k % 40), 20 + (k % 40), 64, 48)).clone(), k);
  };
  MotionEstimator saver(MotionOptions{});
  for (int k = 1; k <= 6; ++k) saver.process(small_frame(k));
  const std::vector<uint8_t> good = saver.save_state();
  constexpr size_t kHeader = 28;
  ASSERT_GT(good.size(), kHeader + 3000);
  std::mt19937_64 rng(11);
  int accepted = 0, refused = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    std::vector<uint8_t> bytes = good;
    const int changes = 1 + static_cast<int>(rng() % 4);
    for (int c = 0; c < changes; ++c) {
      // Mostly the fields before and after the image (counts, ids, sizes, doubles), sometimes any byte.
      const size_t span = bytes.size() - kHeader;
      size_t at = kHeader + static_cast<size_t>(rng() % span);
      if (rng() % 2 == 0) at = kHeader + static_cast<size_t>(rng() % 200);
      bytes[at] = static_cast<uint8_t>(rng());
    }
    const uint64_t checksum = fnv1a64(bytes.data() + kHeader, bytes.size() - kHeader);
    std::memcpy(bytes.data() + 20, &checksum, sizeof checksum);
    MotionEstimator target(MotionOptions{});
    try {
      target.restore_state(bytes);
    } catch (const InputError&) {
      ++refused;
      continue;
    }
    ++accepted;
    for (int k = 7; k <= 8; ++k) target.process(small_frame(k));
  }
  std::printf("mutated states: %d refused, %d accepted and carried through two frames\n", refused, accepted);
  EXPECT_GT(refused, 0);
  EXPECT_GT(accepted, 0);
}

}  // namespace
}  // namespace uavmot::motion
