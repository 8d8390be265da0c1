// Video source and frame sink as two separate processes over real Fast DDS.

#include <algorithm>
#include <filesystem>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "child_process.hpp"
#include "uavmot/build_paths/build_paths.hpp"
#include "uavmot/core/checksum.hpp"
#include "uavmot/source/frame_source.hpp"

namespace uavmot {
namespace {
using testing::binary;
using testing::ChildProcess;

const std::string kClif = build_paths::data_dir() + "/clif2007/jpg";

struct ReceivedFrame {
  int64_t index = 0;
  int64_t capture_time_ns = 0;
  uint64_t checksum = 0;
  int64_t source_time_ns = 0;
};

std::vector<ReceivedFrame> read_frames_csv(const std::string& path) {
  std::vector<ReceivedFrame> frames;
  std::istringstream in(testing::read_file(path));
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::stringstream row(line);
    for (std::string cell; std::getline(row, cell, ',');) cells.push_back(cell);
    if (cells.size() != 10) continue;
    frames.push_back({std::stoll(cells[1]), std::stoll(cells[2]), std::stoull(cells[7], nullptr, 16), std::stoll(cells[9])});
  }
  return frames;
}

// The source's camera clock: frame `index` is captured (index - 1) / rate after the stream start.
int64_t capture_offset_ns(int64_t index, double rate) { return static_cast<int64_t>((index - 1) * 1e9 / rate + 0.5); }

TEST(FrameTransport, LosslessDeliversEveryFrameInOrderBitIdentical) {
  const std::string out = testing::fresh_dir("frame_transport_lossless");
  ChildProcess sink({binary("uavmot-framesink"), "--out", out, "--domain", "11", "--idle-timeout", "60"}, out + "/sink.log");
  ChildProcess source({binary("uavmot"), "source", kClif, "--domain", "11", "--mode", "lossless"}, out + "/source.log");
  ASSERT_EQ(source.wait(std::chrono::seconds(120)), 0) << source.log();
  ASSERT_EQ(sink.wait(std::chrono::seconds(30)), 0) << sink.log();

  // What the sink received, against the same frames decoded here.
  const auto received = read_frames_csv(out + "/frames.csv");
  auto frames = source::open_frame_source({.path = kClif});
  Frame frame;
  size_t i = 0;
  while (frames->next(frame)) {
    ASSERT_LT(i, received.size()) << "frame " << frame.index << " never arrived";
    EXPECT_EQ(received[i].index, frame.index);
    EXPECT_EQ(received[i].checksum, fnv1a64(frame.image.data, frame.image.total())) << "frame " << frame.index;
    ++i;
  }
  EXPECT_EQ(i, 250u);
  EXPECT_EQ(received.size(), 250u);
}

TEST(FrameTransport, RateModeTimestampsAndPacesAtTheRequestedRate) {
  const std::string out = testing::fresh_dir("frame_transport_rate");
  constexpr double kRate = 40.0;
  constexpr int kFrames = 60;
  ChildProcess sink({binary("uavmot-framesink"), "--out", out, "--domain", "12", "--mode", "live"}, out + "/sink.log");
  ChildProcess source({binary("uavmot-source"), kClif, "--domain", "12", "--mode", "live", "--rate", "40", "--count",
                       std::to_string(kFrames)},
                      out + "/source.log");
  ASSERT_EQ(source.wait(std::chrono::seconds(60)), 0) << source.log();
  ASSERT_EQ(sink.wait(std::chrono::seconds(30)), 0) << sink.log();
  const auto received = read_frames_csv(out + "/frames.csv");
  ASSERT_GE(received.size(), static_cast<size_t>(kFrames * 0.9)) << "live mode over shared memory should lose little";
  // Capture times are the stream's start on the wall clock plus exactly (index - 1) / rate. The
  // stream starts once every reader acknowledged the first frame, which keeps the time it was sent
  // with (no later than that start).
  ASSERT_GE(received.size(), 2u);
  const auto& second = received[1];
  const int64_t start_ns = second.capture_time_ns - capture_offset_ns(second.index, kRate);
  for (const auto& f : received) {
    if (f.index == 1) {
      EXPECT_LE(f.capture_time_ns, start_ns);
      EXPECT_GT(f.capture_time_ns, start_ns - 2'000'000'000LL) << "the first frame waited more than 2 s";
      continue;
    }
    EXPECT_EQ(f.capture_time_ns - start_ns, capture_offset_ns(f.index, kRate));
  }
  // Publication is paced: the span of DDS source timestamps matches the rate (loose bound: a shared machine).
  const double span_s = (received.back().source_time_ns - received.front().source_time_ns) * 1e-9;
  const double expected_s = (received.back().index - received.front().index) / kRate;
  EXPECT_NEAR(span_s, expected_s, 0.25 * expected_s);
}

// A camera does not wait: a live source that cannot decode at the requested rate (1 kHz here)
// publishes on schedule and passes over the frames it is late for, counting them on uavmot/health,
// instead of falling further and further behind.
TEST(FrameTransport, LiveSourceSkipsFramesItIsLateForAndCountsThem) {
  const std::string out = testing::fresh_dir("frame_transport_live_skip");
  // 8 s of stream at 5 kHz, from the 250 CLIF images looped. An idle core here decodes about
  // 600 of these JPEGs a second (1 kHz was not enough to fall behind), so the source must skip.
  constexpr double kRate = 5000.0;
  constexpr int kFrames = 40000;
  ChildProcess sink({binary("uavmot-framesink"), "--out", out, "--domain", "140", "--mode", "live"}, out + "/sink.log");
  ChildProcess source({binary("uavmot-source"), kClif, "--domain", "140", "--mode", "live", "--rate", std::to_string(static_cast<int>(kRate)), "--loop",
                       "--count", std::to_string(kFrames)},
                      out + "/source.log");
  // While it runs, the health topic shows the skipped frames as drops.
  nlohmann::json source_row;
  for (int poll = 0; poll < 5 && source_row.is_null(); ++poll) {
    ChildProcess status({binary("uavmot"), "status", "--once", "--json", "--wait", "2", "--domain", "140"},
                        out + "/status_" + std::to_string(poll) + ".log");
    ASSERT_TRUE(status.wait(std::chrono::seconds(30)).has_value());
    std::istringstream lines(status.log());
    for (std::string line; std::getline(lines, line);) {
      if (!nlohmann::json::accept(line)) continue;
      for (const auto& row : nlohmann::json::parse(line)) {
        if (row["component"] == "source" && row["state"] == "running" && row["dropped"].get<uint64_t>() > 0) source_row = row;
      }
    }
  }
  ASSERT_FALSE(source_row.is_null()) << "no running source reporting drops; source log:\n" << source.log();
  EXPECT_EQ(source_row["frames_in"].get<uint64_t>(), source_row["frames_out"].get<uint64_t>() + source_row["dropped"].get<uint64_t>());

  ASSERT_EQ(source.wait(std::chrono::seconds(120)), 0) << source.log();
  ASSERT_EQ(sink.wait(std::chrono::seconds(30)), 0) << sink.log();
  // "published P frames in ... , skipped S it was late for": every input frame is one or the other.
  const std::string log = source.log();
  const auto published_at = log.rfind("published ");
  const auto skipped_at = log.find("skipped ", published_at);
  ASSERT_NE(skipped_at, std::string::npos) << log;
  const long published = std::stol(log.substr(published_at + 10));
  const long skipped = std::stol(log.substr(skipped_at + 8));
  EXPECT_EQ(published + skipped, kFrames) << log;
  EXPECT_GT(skipped, kFrames / 2) << "decoding 668x1004 JPEGs at 5 kHz cannot keep up";

  const auto received = read_frames_csv(out + "/frames.csv");
  ASSERT_GT(received.size(), 10u);
  EXPECT_LE(static_cast<long>(received.size()), published);
  // The camera clock starts once the first frame is acknowledged (see the rate test): measured
  // from the second frame received.
  const int64_t start_ns = received[1].capture_time_ns - capture_offset_ns(received[1].index, kRate);
  std::vector<double> late_ms;
  for (size_t i = 0; i < received.size(); ++i) {
    if (i > 0) {
      EXPECT_GT(received[i].index, received[i - 1].index);
    }
    EXPECT_LE(received[i].index, kFrames);
    // Indices keep the input numbering, so capture times stay on the camera's clock.
    if (received[i].index == 1) {
      EXPECT_LE(received[i].capture_time_ns, start_ns);
    } else {
      EXPECT_EQ(received[i].capture_time_ns - start_ns, capture_offset_ns(received[i].index, kRate));
    }
    late_ms.push_back((received[i].source_time_ns - received[i].capture_time_ns) * 1e-6);
  }
  // On schedule: a frame goes out within a few decode times of when it was due. A source that did
  // not skip would publish about one frame in five on time here and end seconds behind.
  std::sort(late_ms.begin(), late_ms.end());
  EXPECT_LT(late_ms[late_ms.size() / 2], 50.0);
  EXPECT_LT(late_ms.back(), 1000.0);
}

TEST(FrameTransport, SourceFailsClearlyOnBadInput) {
  const std::string out = testing::fresh_dir("frame_transport_bad_input");
  ChildProcess missing({binary("uavmot-source"), "/nonexistent/clip.mp4", "--domain", "13"}, out + "/missing.log");
  EXPECT_EQ(missing.wait(std::chrono::seconds(20)), 2);
  EXPECT_NE(missing.log().find("does not exist"), std::string::npos) << missing.log();
  ChildProcess bad_flag({binary("uavmot-source"), kClif, "--mode", "sideways"}, out + "/flag.log");
  EXPECT_NE(bad_flag.wait(std::chrono::seconds(20)), 0);
}

}  // namespace
}  // namespace uavmot
