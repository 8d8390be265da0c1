// CDR bytes as the recorder stores them: identical to what Fast DDS sends, and decoded back to
// the same sample.

#include "uavmot/dds/cdr_sample.hpp"

#include <mutex>
#include <set>
#include <thread>

#include <gtest/gtest.h>

#include "motionPubSubTypes.h"
#include "tracksPubSubTypes.h"
#include "uavmot/dds/participant.hpp"
#include "uavmot/record/qos_description.hpp"

namespace uavmot::record {
namespace {

using dds::from_cdr;
using dds::to_cdr;

msg::MotionEstimate make_motion(int64_t index) {
  msg::MotionEstimate m;
  m.stream_id("uav1");
  m.frame_index(index);
  m.capture_time_ns(1'700'000'000'000'000'000 + index * 40'000'000);
  m.image_width(1920);
  m.image_height(1080);
  m.homography({1.0, 0.01 * static_cast<double>(index), 3.5, 0.0, 1.0, -2.25, 1e-6, 0.0, 1.0});
  m.valid(true);
  m.inliers(static_cast<uint32_t>(200 + index));
  m.residual_px(0.375);
  for (int i = 0; i < 3; ++i) {
    msg::Feature f;
    f.id(static_cast<uint64_t>(index * 10 + i));
    f.x(10.5 * i);
    f.y(-3.25);
    f.vx(0.5);
    f.age(static_cast<uint32_t>(i));
    f.moving(i == 1);
    m.features().push_back(f);
  }
  return m;
}

TEST(CdrPayload, RoundTripGivesTheSameSample) {
  msg::MotionEstimatePubSubType type;
  auto sample = make_motion(7);
  const auto bytes = to_cdr(type, sample);
  ASSERT_GE(bytes.size(), 4u);
  // Encapsulation header: CDR little-endian, as Fast DDS 2.9 sends on x86.
  EXPECT_EQ(bytes[0], 0x00);
  EXPECT_EQ(bytes[1], 0x01);
  msg::MotionEstimate back;
  from_cdr(type, bytes.data(), bytes.size(), back, "test");
  EXPECT_TRUE(back == sample);
  EXPECT_EQ(back.features().size(), 3u);
  EXPECT_EQ(to_cdr(type, back), bytes);
}

TEST(CdrPayload, GeneratedSerializerBytesPaddedToFourBytes) {
  msg::MotionEstimatePubSubType type;
  auto list = make_motion(2);  // 301 CDR bytes + the 4-byte header: needs 3 bytes of padding
  eprosima::fastrtps::rtps::SerializedPayload_t payload(type.getSerializedSizeProvider(&list)());
  ASSERT_TRUE(type.serialize(&list, &payload));
  std::vector<uint8_t> expected(payload.data, payload.data + payload.length);
  ASSERT_NE(expected.size() % 4, 0u) << "pick a sample whose CDR length needs padding";
  expected.resize((expected.size() + 3) / 4 * 4, 0);
  EXPECT_EQ(to_cdr(type, list), expected);
}

TEST(CdrPayload, DamagedBytesAreInputErrors) {
  msg::MotionEstimatePubSubType type;
  auto sample = make_motion(1);
  auto bytes = to_cdr(type, sample);
  msg::MotionEstimate back;
  EXPECT_THROW(from_cdr(type, bytes.data(), 2, back, "short"), InputError);
  EXPECT_THROW(from_cdr(type, bytes.data(), bytes.size() / 2, back, "cut"), InputError);
}

// A reader type that keeps the serialized bytes it received: what travelled on the wire.
struct WireSpyType : msg::MotionEstimatePubSubType {
  static std::mutex& mutex() {
    static std::mutex m;
    return m;
  }
  static std::vector<std::vector<uint8_t>>& seen() {
    static std::vector<std::vector<uint8_t>> s;
    return s;
  }
  bool deserialize(eprosima::fastrtps::rtps::SerializedPayload_t* payload, void* data) override {
    {
      std::lock_guard<std::mutex> lock(mutex());
      seen().emplace_back(payload->data, payload->data + payload->length);
    }
    return msg::MotionEstimatePubSubType::deserialize(payload, data);
  }
};

TEST(CdrPayload, RecordedBytesEqualTheBytesOnTheWire) {
  dds::DdsOptions o;
  o.domain_id = 54;
  o.participant_name = "pub";
  dds::Participant publisher_side(o);
  o.participant_name = "sub";
  dds::Participant subscriber_side(o);
  auto writer = publisher_side.make_writer<msg::MotionEstimatePubSubType>(dds::kMotionTopic, dds::TopicClass::Chain);
  auto reader = subscriber_side.make_reader<WireSpyType>(dds::kMotionTopic, dds::TopicClass::Chain);
  ASSERT_TRUE(writer->wait_for_matched(1, std::chrono::seconds(10)));
  writer->set_required_readers(1);

  std::vector<msg::MotionEstimate> sent;
  for (int i = 1; i <= 5; ++i) {
    sent.push_back(make_motion(i));
    ASSERT_TRUE(writer->write_reliably(sent.back()));
  }
  ASSERT_TRUE(writer->flush());
  msg::MotionEstimatePubSubType type;
  std::vector<msg::MotionEstimate> received;
  msg::MotionEstimate sample;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (received.size() < sent.size() && std::chrono::steady_clock::now() < deadline) {
    if (reader->take(sample)) {
      received.push_back(sample);
    } else {
      reader->wait_for_data(std::chrono::milliseconds(50));
    }
  }
  ASSERT_EQ(received.size(), sent.size());
  std::lock_guard<std::mutex> lock(WireSpyType::mutex());
  // Fast DDS may deserialize a payload more than once; every payload seen is one of the samples.
  auto text = [](const std::vector<uint8_t>& b) { return std::string(b.begin(), b.end()); };
  std::set<std::string> wire, recorded;
  for (const auto& b : WireSpyType::seen()) wire.insert(text(b));
  for (size_t i = 0; i < sent.size(); ++i) {
    // The recorder re-serializes the sample it took: the same bytes that arrived.
    recorded.insert(text(to_cdr(type, received[i])));
    EXPECT_TRUE(wire.count(text(to_cdr(type, received[i])))) << "sample " << i << " re-serialized differs from the wire";
    EXPECT_TRUE(received[i] == sent[i]);
  }
  EXPECT_EQ(wire, recorded);
  // The QoS the recorder describes for a lossless chain reader.
  const auto qos = describe_qos(reader->native()->get_qos());
  EXPECT_EQ(qos.reliability, "RELIABLE");
  EXPECT_EQ(qos.history, "KEEP_ALL");
}

}  // namespace
}  // namespace uavmot::record
