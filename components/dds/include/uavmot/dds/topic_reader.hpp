#pragma once
// A typed DataReader: take valid samples, wait for data, count what arrived.

#include <chrono>
#include <string>

#include <fastdds/dds/core/status/SubscriptionMatchedStatus.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>

namespace uavmot::dds {

template <class PubSubType>
class TopicReader {
 public:
  using Sample = typename PubSubType::type;

  TopicReader(eprosima::fastdds::dds::DataReader* reader, std::string topic) : reader_(reader), topic_(std::move(topic)) {}

  // Takes the next sample with data; skips instance-state notifications. False when none is waiting.
  bool take(Sample& sample, eprosima::fastdds::dds::SampleInfo* info_out = nullptr) {
    eprosima::fastdds::dds::SampleInfo info;
    while (reader_->take_next_sample(&sample, &info) == eprosima::fastrtps::types::ReturnCode_t::RETCODE_OK) {
      if (!info.valid_data) continue;
      ++samples_taken_;
      bytes_taken_ += type_.getSerializedSizeProvider(&sample)();
      if (info_out) *info_out = info;
      return true;
    }
    return false;
  }

  // Waits until a sample is waiting; false on timeout.
  bool wait_for_data(std::chrono::milliseconds timeout) {
    if (reader_->get_unread_count() > 0) return true;
    const auto ns = std::chrono::duration_cast<std::chrono::nanoseconds>(timeout).count();
    return reader_->wait_for_unread_message(
        eprosima::fastrtps::Duration_t(static_cast<int32_t>(ns / 1000000000), static_cast<uint32_t>(ns % 1000000000)));
  }

  uint64_t unread() const { return reader_->get_unread_count(); }

  int matched() const {
    eprosima::fastdds::dds::SubscriptionMatchedStatus status;
    reader_->get_subscription_matched_status(status);
    return status.current_count;
  }

  uint64_t samples_taken() const { return samples_taken_; }
  uint64_t bytes_taken() const { return bytes_taken_; }  // serialized payload bytes of the samples taken
  const std::string& topic() const { return topic_; }
  eprosima::fastdds::dds::DataReader* native() const { return reader_; }

 private:
  eprosima::fastdds::dds::DataReader* reader_;
  std::string topic_;
  PubSubType type_;
  uint64_t samples_taken_ = 0;
  uint64_t bytes_taken_ = 0;
};

}  // namespace uavmot::dds
