#pragma once
// A DomainParticipant built from the XML profiles in bringup/qos, with one publisher and one
// subscriber, that hands out typed writers and readers. Deleting it deletes every entity.

#include <chrono>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/domain/qos/DomainParticipantQos.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/topic/Topic.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>

#include "uavmot/dds/topic_reader.hpp"
#include "uavmot/dds/topic_writer.hpp"
#include "uavmot/dds/topics.hpp"

namespace uavmot::dds {

// A Fast DDS flow controller (configured in C++: Fast DDS 2.9 has no XML for it): the writers
// that name it send at most `bits_per_second` together, newest samples first to go when over.
struct FlowLimit {
  std::string name;
  uint64_t bits_per_second = 0;
};

struct DdsOptions {
  int domain_id = 0;
  std::string profiles_file;                  // empty: $UAVMOT_QOS_PROFILES, then the installed/default file
  std::string participant_profile = "local";  // "local" (shared memory) or "udp" (between hosts)
  std::string participant_name = "uavmot";
  // "IP:PORT" of a Fast DDS Discovery Server (server id 0) to be a client of, for links without
  // multicast; empty: SIMPLE discovery (unless Fast DDS picks up $ROS_DISCOVERY_SERVER itself).
  std::string discovery_server;
  std::vector<FlowLimit> flow_limits;
  DeliveryMode mode = DeliveryMode::Lossless;
};

// Where the default profiles file is, for messages and `--help`.
std::string default_profiles_file();

class Participant {
 public:
  // Throws InputError when the profiles file or a profile is missing or invalid.
  explicit Participant(DdsOptions options);
  ~Participant();
  Participant(const Participant&) = delete;
  Participant& operator=(const Participant&) = delete;

  const DdsOptions& options() const { return options_; }

  // `flow`: the name of one of options().flow_limits; the writer then publishes asynchronously
  // through that flow controller.
  template <class PubSubType>
  std::unique_ptr<TopicWriter<PubSubType>> make_writer(const std::string& topic_name, TopicClass topic_class,
                                                       const std::string& flow = "") {
    auto* topic = topic_for(topic_name, eprosima::fastdds::dds::TypeSupport(new PubSubType()));
    auto* writer = create_writer(topic, writer_profile(topic_class, options_.mode), flow, "");
    return std::make_unique<TopicWriter<PubSubType>>(writer, topic_name);
  }
  // A writer in DDS partition `partition` (health reports: their component's, health_partitions.hpp).
  // Throws InputError when access control refuses it.
  template <class PubSubType>
  std::unique_ptr<TopicWriter<PubSubType>> make_writer_in(const std::string& partition, const std::string& topic_name,
                                                          TopicClass topic_class) {
    auto* topic = topic_for(topic_name, eprosima::fastdds::dds::TypeSupport(new PubSubType()));
    auto* writer = create_writer(topic, writer_profile(topic_class, options_.mode), "", partition);
    return std::make_unique<TopicWriter<PubSubType>>(writer, topic_name);
  }
  // A reader of partition `partition` only ("*": all of them).
  template <class PubSubType>
  std::unique_ptr<TopicReader<PubSubType>> make_reader_in(const std::string& partition, const std::string& topic_name,
                                                          TopicClass topic_class) {
    auto* topic = topic_for(topic_name, eprosima::fastdds::dds::TypeSupport(new PubSubType()));
    auto* reader = create_reader(topic, reader_profile(topic_class, options_.mode), partition);
    return std::make_unique<TopicReader<PubSubType>>(reader, topic_name);
  }

  template <class PubSubType>
  std::unique_ptr<TopicReader<PubSubType>> make_reader(const std::string& topic_name, TopicClass topic_class) {
    return make_reader<PubSubType>(topic_name, reader_profile(topic_class, options_.mode));
  }
  // With a named reader profile of the profiles file (e.g. the recorder's frames_record_reader).
  // Health readers read every component's partition (health_partitions.hpp).
  template <class PubSubType>
  std::unique_ptr<TopicReader<PubSubType>> make_reader(const std::string& topic_name, const std::string& profile) {
    auto* topic = topic_for(topic_name, eprosima::fastdds::dds::TypeSupport(new PubSubType()));
    auto* reader = create_reader(topic, profile, topic_name == kHealthTopic ? "*" : "");
    return std::make_unique<TopicReader<PubSubType>>(reader, topic_name);
  }
  // A reader of only the samples whose stream_id is one of STREAM_IDS (all ids when empty): a
  // ContentFilteredTopic that Fast DDS 2.9 evaluates before a sample enters the reader's history,
  // so other ids never take one of its max_instances slots (docs/topics.md, "Instance limits").
  template <class PubSubType>
  std::unique_ptr<TopicReader<PubSubType>> make_reader(const std::string& topic_name, TopicClass topic_class,
                                                       const std::vector<std::string>& stream_ids) {
    if (stream_ids.empty()) return make_reader<PubSubType>(topic_name, topic_class);
    auto* topic = topic_for(topic_name, eprosima::fastdds::dds::TypeSupport(new PubSubType()));
    add_stream_id_reader(topic->get_type_name(), [](eprosima::fastrtps::rtps::SerializedPayload_t& payload) {
      PubSubType type;
      typename PubSubType::type sample;
      return type.deserialize(&payload, &sample) ? std::optional<std::string>(sample.stream_id().to_string()) : std::nullopt;
    });
    auto* reader = create_reader(stream_filtered(topic, stream_ids), reader_profile(topic_class, options_.mode), "");
    return std::make_unique<TopicReader<PubSubType>>(reader, topic_name);
  }
  // Deletes a reader made here before the participant goes (readers that come and go, e.g. the
  // Foxglove bridge's, which reads a topic only while a viewer watches it).
  template <class PubSubType>
  void delete_reader(std::unique_ptr<TopicReader<PubSubType>> reader) {
    if (reader) delete_native_reader(reader->native());
  }

 private:
  eprosima::fastdds::dds::DomainParticipant* create_on_fresh_ports(eprosima::fastdds::dds::DomainParticipantQos qos);
  eprosima::fastdds::dds::Topic* topic_for(const std::string& name, eprosima::fastdds::dds::TypeSupport type);
  // `partition` "": the default partition.
  eprosima::fastdds::dds::DataWriter* create_writer(eprosima::fastdds::dds::Topic* topic, const std::string& profile,
                                                    const std::string& flow, const std::string& partition);
  eprosima::fastdds::dds::DataReader* create_reader(eprosima::fastdds::dds::TopicDescription* topic,
                                                    const std::string& profile, const std::string& partition);
  void delete_native_reader(eprosima::fastdds::dds::DataReader* reader);  // from whichever subscriber made it
  // Partitions are publisher/subscriber QoS in DDS: one of each per partition, made when first needed.
  eprosima::fastdds::dds::Publisher* publisher_for(const std::string& partition);
  eprosima::fastdds::dds::Subscriber* subscriber_for(const std::string& partition);
  // The stream id of a serialized sample of a type; nullopt when it does not deserialize.
  using StreamIdOf = std::function<std::optional<std::string>(eprosima::fastrtps::rtps::SerializedPayload_t&)>;
  void add_stream_id_reader(const std::string& type_name, StreamIdOf stream_id_of);
  eprosima::fastdds::dds::TopicDescription* stream_filtered(eprosima::fastdds::dds::Topic* topic,
                                                            const std::vector<std::string>& stream_ids);

  DdsOptions options_;
  eprosima::fastdds::dds::DomainParticipant* participant_ = nullptr;
  eprosima::fastdds::dds::Publisher* publisher_ = nullptr;
  eprosima::fastdds::dds::Subscriber* subscriber_ = nullptr;
  std::map<std::string, eprosima::fastdds::dds::Topic*> topics_;
  std::map<std::string, eprosima::fastdds::dds::Publisher*> partition_publishers_;
  std::map<std::string, eprosima::fastdds::dds::Subscriber*> partition_subscribers_;
  // Outlive participant_: the destructor deletes its entities (the filtered topics) first.
  class StreamIdFilterFactory;
  std::unique_ptr<StreamIdFilterFactory> stream_filter_;
  class RejectLogger;
  std::unique_ptr<RejectLogger> reject_logger_;
};

}  // namespace uavmot::dds
