#include "uavmot/dds/frame_convert.hpp"

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

namespace uavmot::dds {
namespace {

Frame random_frame(int type) {
  Frame frame;
  frame.stream_id = "uav7";
  frame.index = 42;
  frame.capture_time_ns = 1'680'000'000;
  frame.image.create(31, 17, type);
  cv::RNG rng(1);
  rng.fill(frame.image, cv::RNG::UNIFORM, 0, 256);
  return frame;
}

TEST(FrameConvert, RoundTripIsBitExactForMonoAndColor) {
  for (int type : {CV_8UC1, CV_8UC3}) {
    const Frame in = random_frame(type);
    const msg::Frame sample = to_msg(in);
    EXPECT_EQ(sample.encoding(), type == CV_8UC1 ? msg::Encoding::MONO8 : msg::Encoding::BGR8);
    std::string why;
    const auto out = from_msg(sample, why);
    ASSERT_TRUE(out) << why;
    EXPECT_EQ(out->stream_id, "uav7");
    EXPECT_EQ(out->index, 42);
    EXPECT_EQ(out->capture_time_ns, 1'680'000'000);
    EXPECT_EQ(out->image.type(), type);
    EXPECT_EQ(cv::norm(out->image, in.image, cv::NORM_INF), 0.0);
  }
}

TEST(FrameConvert, ViewSharesTheSamplesPixelsAndValidatesTheSame) {
  for (int type : {CV_8UC1, CV_8UC3}) {
    const Frame in = random_frame(type);
    msg::Frame sample = to_msg(in);
    std::string why;
    const auto view = view_msg(sample, why);
    ASSERT_TRUE(view) << why;
    EXPECT_EQ(view->index, 42);
    EXPECT_EQ(view->image.type(), type);
    EXPECT_EQ(view->image.data, sample.data().data()) << "no copy";
    EXPECT_EQ(cv::norm(view->image, in.image, cv::NORM_INF), 0.0);
  }
  msg::Frame short_sample = to_msg(random_frame(CV_8UC1));
  short_sample.data().pop_back();
  std::string why;
  EXPECT_FALSE(view_msg(short_sample, why));
  EXPECT_NE(why.find("expected 527"), std::string::npos) << why;
}

TEST(FrameConvert, JpegPreviewDecodesToTheSameSizeAndCloseToThePixels) {
  Frame in;
  in.stream_id = "uav7";
  in.index = 3;
  in.image.create(48, 64, CV_8UC1);
  for (int y = 0; y < in.image.rows; ++y) {
    for (int x = 0; x < in.image.cols; ++x) in.image.at<uint8_t>(y, x) = static_cast<uint8_t>(2 * x + y);  // smooth
  }
  const msg::Frame sample = to_jpeg_msg(in, 90);
  EXPECT_EQ(sample.encoding(), msg::Encoding::JPEG);
  EXPECT_LT(sample.data().size(), in.image.total());  // compressed
  std::string why;
  const auto out = from_msg(sample, why);
  ASSERT_TRUE(out) << why;
  EXPECT_EQ(out->index, 3);
  EXPECT_EQ(out->image.size(), in.image.size());
  EXPECT_LT(cv::norm(out->image, in.image, cv::NORM_L1) / static_cast<double>(in.image.total()), 2.0);
}

TEST(FrameConvert, RejectsMalformedSamplesWithAReason) {
  msg::Frame sample = to_msg(random_frame(CV_8UC1));
  std::string why;
  sample.data().pop_back();
  EXPECT_FALSE(from_msg(sample, why));
  EXPECT_NE(why.find("expected 527"), std::string::npos) << why;

  sample = to_msg(random_frame(CV_8UC1));
  sample.width(0);
  EXPECT_FALSE(from_msg(sample, why));

  sample = to_msg(random_frame(CV_8UC1));
  sample.frame_index(0);
  EXPECT_FALSE(from_msg(sample, why));

  sample = to_msg(random_frame(CV_8UC1));
  sample.encoding(msg::Encoding::JPEG);  // raw bytes announced as JPEG
  EXPECT_FALSE(from_msg(sample, why));
}

TEST(FrameConvert, JpegDecodesToTheAnnouncedSize) {
  for (int type : {CV_8UC1, CV_8UC3}) {
    const Frame in = random_frame(type);
    msg::Frame sample = to_msg(in);
    sample.encoding(msg::Encoding::JPEG);
    cv::imencode(".jpg", in.image, sample.data());
    std::string why;
    const auto out = from_msg(sample, why);
    ASSERT_TRUE(out) << why;
    EXPECT_EQ(out->image.type(), type);
    EXPECT_EQ(out->image.size(), in.image.size());
    sample.width(sample.width() + 1);
    EXPECT_FALSE(from_msg(sample, why));
  }
}

TEST(FrameConvert, EmptyOrTruncatedJpegIsRejectedNotThrown) {
  // Found by sample_validators_fuzz (tests/fuzz/regressions/sample_validators/empty_jpeg_frame):
  // an empty JPEG payload made cv::imdecode throw out of the motion node's receive path.
  msg::Frame sample = to_msg(random_frame(CV_8UC1));
  sample.encoding(msg::Encoding::JPEG);
  sample.data().clear();
  std::string why;
  EXPECT_FALSE(from_msg(sample, why));
  EXPECT_NE(why.find("JPEG"), std::string::npos) << why;

  cv::imencode(".jpg", random_frame(CV_8UC1).image, sample.data());
  sample.data().resize(20);  // SOI and part of a header
  EXPECT_FALSE(from_msg(sample, why));
}

}  // namespace
}  // namespace uavmot::dds
