#include "uavmot/dds/participant.hpp"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <mutex>
#include <optional>
#include <set>

#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/log/Log.hpp>
#include <fastdds/rtps/flowcontrol/FlowControllerDescriptor.hpp>
#include <fastdds/rtps/transport/shared_mem/SharedMemTransportDescriptor.h>
#include <fastrtps/utils/IPLocator.h>
#include <fastdds/dds/publisher/qos/DataWriterQos.hpp>
#include <fastdds/dds/subscriber/qos/DataReaderQos.hpp>
#include <fastdds/dds/subscriber/DataReaderListener.hpp>
#include <fastdds/dds/topic/ContentFilteredTopic.hpp>
#include <fastdds/dds/topic/IContentFilterFactory.hpp>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include "shm_ports.hpp"
#include "uavmot/build_paths/build_paths.hpp"
#include "uavmot/core/error.hpp"

namespace uavmot::dds {
namespace fdds = eprosima::fastdds::dds;
namespace fs = std::filesystem;
namespace {

fs::path executable_dir() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  return ec ? fs::path() : exe.parent_path();
}

// Fast DDS prints only its errors; UAVMOT_DDS_LOG=warning (or info) shows what it otherwise keeps
// to itself, e.g. a shared-memory port found unhealthy or a security handshake that failed.
void apply_dds_log_level_once() {
  static std::once_flag once;
  std::call_once(once, [] {
    const char* env = std::getenv("UAVMOT_DDS_LOG");
    if (!env || !*env) return;
    using eprosima::fastdds::dds::Log;
    const std::map<std::string, Log::Kind> levels = {{"error", Log::Kind::Error}, {"warning", Log::Kind::Warning}, {"info", Log::Kind::Info}};
    const auto level = levels.find(env);
    if (level == levels.end()) throw InputError(std::string("UAVMOT_DDS_LOG='") + env + "': expected error, warning or info");
    Log::SetVerbosity(level->second);
  });
}

void load_profiles_once(const std::string& file) {
  static std::mutex mutex;
  static std::set<std::string> loaded;
  std::lock_guard<std::mutex> lock(mutex);
  if (loaded.count(file)) return;
  if (!fs::is_regular_file(file)) throw InputError("QoS profiles file '" + file + "' does not exist");
  if (fdds::DomainParticipantFactory::get_instance()->load_XML_profiles_file(file) != ReturnCode_t::RETCODE_OK) {
    throw InputError("QoS profiles file '" + file + "' is not valid Fast DDS XML (see the Fast DDS log above)");
  }
  loaded.insert(file);
}
// Makes the participant a client of the Discovery Server with id 0 at "IP:PORT".
void use_discovery_server(fdds::DomainParticipantQos& qos, const std::string& address) {
  namespace rtps = eprosima::fastrtps::rtps;
  const auto colon = address.rfind(':');
  int port = 0;
  try {
    port = colon == std::string::npos ? 0 : std::stoi(address.substr(colon + 1));
  } catch (const std::exception&) {
  }
  rtps::Locator_t locator;
  if (port <= 0 || port > 65535 || !rtps::IPLocator::setIPv4(locator, address.substr(0, colon))) {
    throw InputError("discovery server '" + address + "' is not IPv4:PORT");
  }
  locator.port = static_cast<uint32_t>(port);
  rtps::RemoteServerAttributes server;
  server.ReadguidPrefix("44.53.00.5f.45.50.52.4f.53.49.4d.41");  // fast-discovery-server -i 0
  server.metatrafficUnicastLocatorList.push_back(locator);
  auto& discovery = qos.wire_protocol().builtin.discovery_config;
  discovery.discoveryProtocol = rtps::DiscoveryProtocol_t::CLIENT;
  discovery.m_DiscoveryServers.push_back(server);
}

bool uses_shared_memory(const fdds::DomainParticipantQos& qos) {
  if (qos.transport().use_builtin_transports) return true;  // Fast DDS's builtins include shared memory
  for (const auto& transport : qos.transport().user_transports) {
    if (std::dynamic_pointer_cast<eprosima::fastdds::rtps::SharedMemTransportDescriptor>(transport)) return true;
  }
  return false;
}
}  // namespace

// Filter class "UAVMOT_STREAM_IDS": a sample passes when its stream_id is one of the filter's
// parameters. Custom rather than Fast DDS's SQL filter, which needs TypeObjects (fastddsgen
// -typeobject), which the IDL build does not generate. Only this process registers it, so the
// writers (other processes) do not filter: every sample is evaluated here, on reception.
// Fast DDS's filter interfaces have no virtual destructors; these classes are final and deleted as themselves.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnon-virtual-dtor"
class Participant::StreamIdFilterFactory final : public fdds::IContentFilterFactory {
 public:
  static constexpr const char* kClass = "UAVMOT_STREAM_IDS";

  void add_type(const std::string& type_name, StreamIdOf stream_id_of) {
    std::lock_guard<std::mutex> lock(mutex_);
    types_.try_emplace(type_name, std::move(stream_id_of));
  }

  ReturnCode_t create_content_filter(const char*, const char* type_name, const fdds::TopicDataType*, const char*,
                                     const ParameterSeq& parameters, fdds::IContentFilter*& filter) override {
    std::lock_guard<std::mutex> lock(mutex_);
    const auto type = types_.find(type_name);
    if (type == types_.end()) return ReturnCode_t::RETCODE_BAD_PARAMETER;
    std::set<std::string> ids;
    for (ParameterSeq::size_type i = 0; i < parameters.length(); ++i) ids.insert(parameters[i]);
    // Replaces the filter of a reader whose parameters change (delete_content_filter frees the old one).
    filter = new Filter(type->second, std::move(ids));
    return ReturnCode_t::RETCODE_OK;
  }
  ReturnCode_t delete_content_filter(const char*, fdds::IContentFilter* filter) override {
    delete static_cast<Filter*>(filter);
    return ReturnCode_t::RETCODE_OK;
  }

 private:
  struct Filter final : fdds::IContentFilter {
    Filter(StreamIdOf of, std::set<std::string> ids) : stream_id_of(std::move(of)), stream_ids(std::move(ids)) {}
    bool evaluate(const SerializedPayload& payload, const FilterSampleInfo&, const GUID_t&) const override {
      // Deserializing only reads the payload.
      const auto id = stream_id_of(const_cast<SerializedPayload&>(payload));
      return id && stream_ids.count(*id) > 0;
    }
    StreamIdOf stream_id_of;
    std::set<std::string> stream_ids;
  };
  std::mutex mutex_;
  std::map<std::string, StreamIdOf> types_;
};
#pragma GCC diagnostic pop

// Warns of samples a reader refused for its instance limit, the one rejection that loses a stream:
// the reader holds max_instances stream ids (alive ones are never evicted in Fast DDS 2.9), and the
// refused sample is never resent.
class Participant::RejectLogger : public fdds::DataReaderListener {
 public:
  void on_sample_rejected(fdds::DataReader* reader, const fdds::SampleRejectedStatus& status) override {
    // A full history (samples, samples per instance) is flow control: a reliable writer sends the
    // sample again, and in lossless mode a busy reader fills its history all the time. Not a loss.
    if (status.last_reason != fdds::REJECTED_BY_INSTANCES_LIMIT) return;
    int64_t count = 0;
    {
      std::lock_guard<std::mutex> lock(mutex_);  // one listener serves every reader of the participant
      count = ++instance_rejections_[reader];
    }
    // First of each reader, then every 100th: a flood must not flood the log.
    if (count != 1 && count % 100 != 0) return;
    fdds::DataReaderQos qos = reader->get_qos();
    spdlog::warn("{}: {} sample(s) of new stream ids rejected: this reader already holds {} stream ids (max_instances); "
                 "those streams are lost to it. Forged ids on the network? Name the expected streams (--stream-id) "
                 "so that others are filtered out first (docs/topics.md)",
                 reader->get_topicdescription()->get_name(), count, qos.resource_limits().max_instances);
  }

 private:
  std::mutex mutex_;
  std::map<const fdds::DataReader*, int64_t> instance_rejections_;
};

std::string default_profiles_file() {
  if (const char* env = std::getenv("UAVMOT_QOS_PROFILES"); env && *env) return env;
  // Installed layout (bin/ beside share/), then bringup/qos of the source tree this was built from.
  const fs::path installed = executable_dir() / ".." / "share" / "uavmot" / "qos" / "uavmot_qos.xml";
  if (fs::is_regular_file(installed)) return fs::weakly_canonical(installed).string();
  return build_paths::source_dir() + "/bringup/qos/uavmot_qos.xml";
}

Participant::Participant(DdsOptions options) : options_(std::move(options)) {
  if (options_.profiles_file.empty()) options_.profiles_file = default_profiles_file();
  apply_dds_log_level_once();
  load_profiles_once(options_.profiles_file);
  auto* factory = fdds::DomainParticipantFactory::get_instance();
  fdds::DomainParticipantQos qos;
  if (factory->get_participant_qos_from_profile(options_.participant_profile, qos) != ReturnCode_t::RETCODE_OK) {
    throw InputError("participant profile '" + options_.participant_profile + "' is not in '" + options_.profiles_file + "'");
  }
  qos.name(options_.participant_name + "@" + std::to_string(::getpid()));
  if (!options_.discovery_server.empty()) use_discovery_server(qos, options_.discovery_server);
  for (const FlowLimit& limit : options_.flow_limits) {
    auto descriptor = std::make_shared<eprosima::fastdds::rtps::FlowControllerDescriptor>();
    descriptor->name = limit.name.c_str();  // options_ lives as long as the participant
    descriptor->scheduler = eprosima::fastdds::rtps::FlowControllerSchedulerPolicy::FIFO;
    descriptor->period_ms = 100;
    // Bytes per 100 ms period; 0 is Fast DDS's "no limit", so at least 1.
    descriptor->max_bytes_per_period =
        static_cast<int32_t>(std::clamp<uint64_t>(limit.bits_per_second / 8 / 10, 1, 2147483647));
    qos.flow_controllers().push_back(descriptor);
  }
  if (qos.wire_protocol().participant_id < 0 && uses_shared_memory(qos)) {
    participant_ = create_on_fresh_ports(qos);
  } else {
    participant_ = factory->create_participant(options_.domain_id, qos);
  }
  if (!participant_) throw InputError("cannot create a DDS participant on domain " + std::to_string(options_.domain_id));
  publisher_ = participant_->create_publisher(fdds::PUBLISHER_QOS_DEFAULT);
  subscriber_ = participant_->create_subscriber(fdds::SUBSCRIBER_QOS_DEFAULT);
  if (!publisher_ || !subscriber_) throw InputError("cannot create DDS publisher/subscriber");
}

// Never takes over the ports of a crashed process (see shm_ports.hpp). A participant id names the
// participant's GUID in its process whatever the domain, so an id that another participant of this
// process has (the downlink and the launcher's watchdog are on two domains) is refused by Fast DDS:
// then the next fresh one.
fdds::DomainParticipant* Participant::create_on_fresh_ports(fdds::DomainParticipantQos qos) {
  auto* factory = fdds::DomainParticipantFactory::get_instance();
  ParticipantIdLock id_lock(options_.domain_id);
  std::set<int> taken_here;
  auto fresh_id = [&] { return fresh_participant_id(options_.domain_id, "/dev/shm", 120, taken_here); };
  for (int attempt = 0; attempt < 8; ++attempt) {
    int id = fresh_id();
    if (id < 0) {
      if (const auto in_use = ports_in_use()) {
        const int freed = reclaim_abandoned_ports(options_.domain_id, *in_use);
        spdlog::info("domain {}: every participant id had left shared-memory ports; freed {} that no process holds",
                     options_.domain_id, freed);
        id = fresh_id();
      } else {
        spdlog::warn("domain {}: every participant id has left shared-memory ports, and /proc does not show which "
                     "are held; leaving the choice to Fast DDS (`fastdds shm clean` removes abandoned ones)",
                     options_.domain_id);
      }
    }
    qos.wire_protocol().participant_id = id;  // -1 (every id held by a live process): Fast DDS chooses
    if (auto* participant = factory->create_participant(options_.domain_id, qos)) return participant;
    if (id < 0) return nullptr;
    spdlog::debug("domain {}: participant id {} is taken in this process; trying the next", options_.domain_id, id);
    taken_here.insert(id);
  }
  return nullptr;
}

void Participant::add_stream_id_reader(const std::string& type_name, StreamIdOf stream_id_of) {
  if (!stream_filter_) {
    stream_filter_ = std::make_unique<StreamIdFilterFactory>();
    if (participant_->register_content_filter_factory(StreamIdFilterFactory::kClass, stream_filter_.get()) !=
        ReturnCode_t::RETCODE_OK) {
      throw InputError("cannot register the stream id content filter");
    }
  }
  stream_filter_->add_type(type_name, std::move(stream_id_of));
}

fdds::TopicDescription* Participant::stream_filtered(fdds::Topic* topic, const std::vector<std::string>& stream_ids) {
  // One reader per topic and participant here; a second gets a name of its own.
  std::string name = topic->get_name() + "/streams";
  for (int n = 2; participant_->lookup_topicdescription(name) != nullptr; ++n) name = topic->get_name() + "/streams" + std::to_string(n);
  // The expression only documents the filter (its class reads the parameters); an empty one would pass everything.
  auto* filtered = participant_->create_contentfilteredtopic(name, topic, "stream_id IN (parameters)", stream_ids,
                                                             StreamIdFilterFactory::kClass);
  if (!filtered) throw InputError("cannot create a stream id filter on '" + topic->get_name() + "'");
  return filtered;
}

Participant::~Participant() {
  if (!participant_) return;
  participant_->delete_contained_entities();
  fdds::DomainParticipantFactory::get_instance()->delete_participant(participant_);
}

fdds::Topic* Participant::topic_for(const std::string& name, fdds::TypeSupport type) {
  if (auto it = topics_.find(name); it != topics_.end()) return it->second;
  if (type.register_type(participant_) != ReturnCode_t::RETCODE_OK &&
      participant_->find_type(type.get_type_name()).empty()) {
    throw InputError("cannot register DDS type " + type.get_type_name());
  }
  auto* topic = participant_->create_topic(name, type.get_type_name(), fdds::TOPIC_QOS_DEFAULT);
  if (!topic) throw InputError("cannot create DDS topic '" + name + "'");
  topics_[name] = topic;
  return topic;
}

void Participant::delete_native_reader(fdds::DataReader* reader) {
  if (subscriber_->delete_datareader(reader) == ReturnCode_t::RETCODE_OK) return;
  for (auto& [partition, subscriber] : partition_subscribers_) {
    if (subscriber->delete_datareader(reader) == ReturnCode_t::RETCODE_OK) return;
  }
}

fdds::Publisher* Participant::publisher_for(const std::string& partition) {
  if (partition.empty()) return publisher_;
  auto& publisher = partition_publishers_[partition];
  if (!publisher) {
    fdds::PublisherQos qos = participant_->get_default_publisher_qos();
    qos.partition().push_back(partition.c_str());
    publisher = participant_->create_publisher(qos);
    if (!publisher) throw InputError("cannot create a DDS publisher for partition '" + partition + "'");
  }
  return publisher;
}

fdds::Subscriber* Participant::subscriber_for(const std::string& partition) {
  if (partition.empty()) return subscriber_;
  auto& subscriber = partition_subscribers_[partition];
  if (!subscriber) {
    fdds::SubscriberQos qos = participant_->get_default_subscriber_qos();
    qos.partition().push_back(partition.c_str());
    subscriber = participant_->create_subscriber(qos);
    if (!subscriber) throw InputError("cannot create a DDS subscriber for partition '" + partition + "'");
  }
  return subscriber;
}

fdds::DataWriter* Participant::create_writer(fdds::Topic* topic, const std::string& profile, const std::string& flow,
                                             const std::string& partition) {
  fdds::DataWriterQos qos;
  if (publisher_->get_datawriter_qos_from_profile(profile, qos) != ReturnCode_t::RETCODE_OK) {
    throw InputError("writer profile '" + profile + "' is not in '" + options_.profiles_file + "'");
  }
  if (!flow.empty()) {
    const auto limit = std::find_if(options_.flow_limits.begin(), options_.flow_limits.end(),
                                    [&](const FlowLimit& l) { return l.name == flow; });
    if (limit == options_.flow_limits.end()) throw InputError("no flow controller '" + flow + "' on this participant");
    qos.publish_mode().kind = fdds::ASYNCHRONOUS_PUBLISH_MODE;
    qos.publish_mode().flow_controller_name = limit->name.c_str();
  }
  auto* writer = publisher_for(partition)->create_datawriter(topic, qos);
  if (!writer) {
    throw InputError("cannot create a writer on '" + topic->get_name() + "' with profile '" + profile + "'" +
                     (partition.empty() ? "" : " in partition '" + partition + "'") + " (refused by access control?)");
  }
  return writer;
}

fdds::DataReader* Participant::create_reader(fdds::TopicDescription* topic, const std::string& profile,
                                             const std::string& partition) {
  fdds::DataReaderQos qos;
  if (subscriber_->get_datareader_qos_from_profile(profile, qos) != ReturnCode_t::RETCODE_OK) {
    throw InputError("reader profile '" + profile + "' is not in '" + options_.profiles_file + "'");
  }
  if (!reject_logger_) reject_logger_ = std::make_unique<RejectLogger>();
  auto* reader =
      subscriber_for(partition)->create_datareader(topic, qos, reject_logger_.get(), fdds::StatusMask::sample_rejected());
  if (!reader) {
    throw InputError("cannot create a reader on '" + topic->get_name() + "' with profile '" + profile + "'" +
                     (partition.empty() ? "" : " in partition '" + partition + "'") + " (refused by access control?)");
  }
  return reader;
}

}  // namespace uavmot::dds
