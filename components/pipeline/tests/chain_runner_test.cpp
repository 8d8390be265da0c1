// run_chain's threading contract: results in frame order, and every failure (in the decoder, in
// a stage, in the consumer) reaches the caller after the frames before it, with no hang.

#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "uavmot/core/error.hpp"
#include "uavmot/pipeline/chain_runner.hpp"

namespace uavmot::pipeline {
namespace {

// Textured frames drifting one pixel per frame; `fail_at` throws from the decoder, `bad_type_at`
// delivers an image motion refuses (16-bit).
class SyntheticSource : public source::FrameSource {
 public:
  SyntheticSource(int count, int fail_at = 0, int bad_type_at = 0) : count_(count), fail_at_(fail_at), bad_type_at_(bad_type_at) {
    cv::RNG rng(7);
    texture_.create(400, 500, CV_8UC1);
    rng.fill(texture_, cv::RNG::UNIFORM, 0, 255);
    cv::GaussianBlur(texture_, texture_, cv::Size(0, 0), 2.0);
    info_.kind = "synthetic";
    info_.size = cv::Size(320, 240);
    info_.frame_count = count;
  }
  bool next(Frame& frame) override {
    if (index_ >= count_) return false;
    ++index_;
    if (index_ == fail_at_) throw InputError("cannot decode frame " + std::to_string(index_));
    frame.stream_id = "test";
    frame.index = index_;
    frame.capture_time_ns = index_ * 40'000'000;
    frame.image = texture_(cv::Rect(index_, index_ / 2, 320, 240)).clone();
    if (index_ == bad_type_at_) frame.image.convertTo(frame.image, CV_16U);
    return true;
  }
  bool skip() override { return ++index_ <= count_; }
  const source::SourceInfo& info() const override { return info_; }
  int64_t skipped() const override { return 0; }

 private:
  int count_, fail_at_, bad_type_at_, index_ = 0;
  cv::Mat texture_;
  source::SourceInfo info_;
};

ChainRunOptions with_threads(int threads) {
  ChainRunOptions o;
  o.threads = threads;
  o.queue_depth = 2;
  return o;
}

class ChainRunner : public ::testing::TestWithParam<int> {};

TEST_P(ChainRunner, ConsumesEveryFrameInOrder) {
  Chain chain{ChainOptions{}};
  std::vector<int64_t> seen;
  const int64_t done = run_chain(std::make_unique<SyntheticSource>(12), chain, with_threads(GetParam()),
                                 [&](const Frame& f, const ChainOutput& out) {
                                   EXPECT_EQ(out.motion.frame_index, f.index);
                                   EXPECT_EQ(out.tracks.frame_index, f.index);
                                   seen.push_back(f.index);
                                 });
  EXPECT_EQ(done, 12);
  ASSERT_EQ(seen.size(), 12u);
  for (size_t i = 0; i < seen.size(); ++i) EXPECT_EQ(seen[i], static_cast<int64_t>(i) + 1);
  EXPECT_EQ(chain.stage_times().frames, 12);
}

TEST_P(ChainRunner, DecoderFailureArrivesAfterTheFramesBeforeIt) {
  Chain chain{ChainOptions{}};
  int64_t consumed = 0;
  EXPECT_THROW(run_chain(std::make_unique<SyntheticSource>(20, 6), chain, with_threads(GetParam()),
                         [&](const Frame&, const ChainOutput&) { ++consumed; }),
               InputError);
  EXPECT_EQ(consumed, 5);
}

TEST_P(ChainRunner, MotionStageFailureArrivesAfterTheFramesBeforeIt) {
  Chain chain{ChainOptions{}};
  int64_t consumed = 0;
  EXPECT_THROW(run_chain(std::make_unique<SyntheticSource>(20, 0, 4), chain, with_threads(GetParam()),
                         [&](const Frame&, const ChainOutput&) { ++consumed; }),
               InputError);
  EXPECT_EQ(consumed, 3);
}

TEST_P(ChainRunner, ConsumerFailureStopsTheOtherStages) {
  Chain chain{ChainOptions{}};
  int64_t consumed = 0;
  EXPECT_THROW(run_chain(std::make_unique<SyntheticSource>(200), chain, with_threads(GetParam()),
                         [&](const Frame& f, const ChainOutput&) {
                           ++consumed;
                           if (f.index == 3) throw std::runtime_error("disk full");
                         }),
               std::runtime_error);
  EXPECT_EQ(consumed, 3);
  EXPECT_LT(chain.stage_times().frames, 10);  // the run stopped, it did not process all 200
}

TEST_P(ChainRunner, StopEndsTheRunEarly) {
  Chain chain{ChainOptions{}};
  std::atomic<int64_t> consumed{0};  // stop() is asked from every stage's thread
  ChainRunOptions o = with_threads(GetParam());
  o.stop = [&] { return consumed.load() >= 4; };
  EXPECT_EQ(run_chain(std::make_unique<SyntheticSource>(200), chain, o, [&](const Frame&, const ChainOutput&) { ++consumed; }), 4);
}

TEST_P(ChainRunner, RestoresOpenCvThreads) {
  const int before = cv::getNumThreads();
  Chain chain{ChainOptions{}};
  run_chain(std::make_unique<SyntheticSource>(3), chain, with_threads(GetParam()), [](const Frame&, const ChainOutput&) {});
  EXPECT_EQ(cv::getNumThreads(), before);
}

INSTANTIATE_TEST_SUITE_P(Threads, ChainRunner, ::testing::Values(1, 2), [](const auto& param_info) {
  return param_info.param == 1 ? std::string("Sequential") : std::string("Pipelined");
});

TEST(ChainRunnerOptions, RefusesOtherThreadCounts) {
  Chain chain{ChainOptions{}};
  EXPECT_THROW(run_chain(std::make_unique<SyntheticSource>(3), chain, with_threads(3), [](const Frame&, const ChainOutput&) {}),
               InvalidArgument);
}

}  // namespace
}  // namespace uavmot::pipeline
