// Foxglove messages encode as XCDR1 little endian with the encapsulation header, field by field as
// idl/foxglove/*.idl orders them: decoded here again with Fast CDR.

#include <gtest/gtest.h>

#include <fastcdr/Cdr.h>
#include <fastcdr/FastBuffer.h>

#include "uavmot/foxglove/encode.hpp"

namespace uavmot::foxglove {
namespace {
using eprosima::fastcdr::Cdr;

struct Decoder {
  explicit Decoder(std::vector<uint8_t>& bytes)
      : buffer(reinterpret_cast<char*>(bytes.data()), bytes.size()), cdr(buffer, Cdr::DEFAULT_ENDIAN, Cdr::DDS_CDR) {
    cdr.read_encapsulation();
  }
  template <class T>
  T get() {
    T v{};
    cdr.deserialize(v);
    return v;
  }
  Color color() { return {get<double>(), get<double>(), get<double>(), get<double>()}; }
  eprosima::fastcdr::FastBuffer buffer;
  Cdr cdr;
};

TEST(Encode, ImageAnnotationsFieldByField) {
  ImageAnnotations m;
  m.circles.push_back({{1, 2}, {3.5, 4.5}, 6.0, 1.5, {0.1, 0.2, 0.3, 0.4}, {0.5, 0.6, 0.7, 0.8}});
  PointsAnnotation p;
  p.timestamp = {10, 20};
  p.type = PointsType::LineLoop;
  p.points = {{1, 2}, {3, 4}, {5, 6}};
  p.outline_color = {1, 0, 0, 1};
  p.outline_colors = {{0, 1, 0, 1}};
  p.fill_color = {0, 0, 0, 0};
  p.thickness = 2.0;
  m.points.push_back(p);
  m.texts.push_back({{7, 8}, {9.0, 10.0}, "#7 45 km/h", 12.0, {0, 1, 0, 1}, {0, 0, 0, 0.6}});
  auto bytes = encode(m);
  ASSERT_GE(bytes.size(), 4u);
  EXPECT_EQ(bytes[0], 0);
  EXPECT_EQ(bytes[1], 1);  // CDR_LE
  EXPECT_EQ(bytes.size() % 4, 0u);

  Decoder d(bytes);
  ASSERT_EQ(d.get<uint32_t>(), 1u);  // circles
  EXPECT_EQ(d.get<uint32_t>(), 1u);
  EXPECT_EQ(d.get<uint32_t>(), 2u);
  EXPECT_EQ(d.get<double>(), 3.5);
  EXPECT_EQ(d.get<double>(), 4.5);
  EXPECT_EQ(d.get<double>(), 6.0);
  EXPECT_EQ(d.get<double>(), 1.5);
  EXPECT_EQ(d.color().a, 0.4);
  EXPECT_EQ(d.color().r, 0.5);
  ASSERT_EQ(d.get<uint32_t>(), 1u);  // points
  EXPECT_EQ(d.get<uint32_t>(), 10u);
  EXPECT_EQ(d.get<uint32_t>(), 20u);
  EXPECT_EQ(d.get<uint32_t>(), 2u);  // LINE_LOOP
  ASSERT_EQ(d.get<uint32_t>(), 3u);
  for (double v : {1, 2, 3, 4, 5, 6}) EXPECT_EQ(d.get<double>(), v);
  EXPECT_EQ(d.color().r, 1.0);
  ASSERT_EQ(d.get<uint32_t>(), 1u);
  EXPECT_EQ(d.color().g, 1.0);
  EXPECT_EQ(d.color().a, 0.0);
  EXPECT_EQ(d.get<double>(), 2.0);
  ASSERT_EQ(d.get<uint32_t>(), 1u);  // texts
  EXPECT_EQ(d.get<uint32_t>(), 7u);
  EXPECT_EQ(d.get<uint32_t>(), 8u);
  EXPECT_EQ(d.get<double>(), 9.0);
  EXPECT_EQ(d.get<double>(), 10.0);
  EXPECT_EQ(d.get<std::string>(), "#7 45 km/h");
  EXPECT_EQ(d.get<double>(), 12.0);
  EXPECT_EQ(d.color().g, 1.0);
  EXPECT_EQ(d.color().a, 0.6);
  EXPECT_LE(d.cdr.getSerializedDataLength(), bytes.size());
  EXPECT_GT(d.cdr.getSerializedDataLength() + 4, bytes.size());  // only the padding to 4 follows
}

TEST(Encode, EmptyAnnotationsAreThreeEmptySequences) {
  const auto bytes = encode(ImageAnnotations{});
  EXPECT_EQ(bytes, (std::vector<uint8_t>{0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0}));
}

TEST(Encode, CompressedImage) {
  CompressedImage m{{5, 6}, "uav1", {0xff, 0xd8, 0xff, 0xd9, 0x00}, "jpeg"};
  auto bytes = encode(m);
  Decoder d(bytes);
  EXPECT_EQ(d.get<uint32_t>(), 5u);
  EXPECT_EQ(d.get<uint32_t>(), 6u);
  EXPECT_EQ(d.get<std::string>(), "uav1");
  ASSERT_EQ(d.get<uint32_t>(), 5u);
  for (uint8_t b : m.data) EXPECT_EQ(d.get<uint8_t>(), b);
  EXPECT_EQ(d.get<std::string>(), "jpeg");
}

TEST(Encode, RawImageLargePayloadFitsItsBound) {
  RawImage m{{1, 0}, "uav1", 1920, 1080, "mono8", 1920, std::vector<uint8_t>(1920 * 1080, 7)};
  auto bytes = encode(m);
  Decoder d(bytes);
  d.get<uint32_t>();
  d.get<uint32_t>();
  EXPECT_EQ(d.get<std::string>(), "uav1");
  EXPECT_EQ(d.get<uint32_t>(), 1920u);
  EXPECT_EQ(d.get<uint32_t>(), 1080u);
  EXPECT_EQ(d.get<std::string>(), "mono8");
  EXPECT_EQ(d.get<uint32_t>(), 1920u);
  EXPECT_EQ(d.get<uint32_t>(), 1920u * 1080u);
  EXPECT_EQ(bytes[bytes.size() - 1], 7);  // 2073600 + header: already a multiple of 4, no padding
}

TEST(Encode, TimeFromNanoseconds) {
  const Time t = time_from_ns(1'700'000'000'123'456'789);
  EXPECT_EQ(t.sec, 1'700'000'000u);
  EXPECT_EQ(t.nsec, 123'456'789u);
  EXPECT_EQ(time_from_ns(-5).sec, 0u);
}

}  // namespace
}  // namespace uavmot::foxglove
