#pragma once
// The uavmot topics a recording can hold: topic name, IDL type, IDL file, QoS class; topic
// selection by fnmatch patterns; where the IDL text is; the channel metadata a recording stores.
// No Fast DDS include: the recorder and replayer add the typed endpoints.

#include <string>
#include <vector>

#include "uavmot/dds/topics.hpp"
#include "uavmot/mcap/types.hpp"

namespace uavmot::record {

struct TopicSpec {
  std::string topic;      // "uavmot/frames"
  std::string type_name;  // fully qualified IDL name, "uavmot::msg::Frame" (the MCAP schema name)
  std::string idl_file;   // file in idl/ that defines it, "frame.idl"
  dds::TopicClass topic_class;
};

// The five uavmot topics, in chain order (frames, motion, segmentation, tracks, health).
const std::vector<TopicSpec>& uavmot_topics();
// The spec of a uavmot topic, or nullptr.
const TopicSpec* find_topic(const std::string& topic);

// True when `name` matches one of the shell wildcard `patterns` (fnmatch: `*` also crosses `/`).
bool matches_any(const std::string& name, const std::vector<std::string>& patterns);
// True when `name` is chosen: matches an include pattern (every name when `include` is empty)
// and no exclude pattern.
bool is_selected(const std::string& name, const std::vector<std::string>& include, const std::vector<std::string>& exclude);
// The uavmot topics chosen by the patterns, in chain order. Throws InputError when an include
// pattern matches no uavmot topic (a typo would otherwise record nothing) or nothing is left.
std::vector<TopicSpec> select_topics(const std::vector<std::string>& include, const std::vector<std::string>& exclude);

// The folder with the .idl files: $UAVMOT_IDL_DIR, then the installed share/uavmot/idl beside
// bin/, then the source tree's idl/. Throws InputError when none holds frame.idl.
std::string find_idl_dir();
// The self-contained IDL text of the topic's type (includes inlined), for its MCAP schema.
std::string schema_text(const TopicSpec& spec, const std::string& idl_dir);

// QoS of a recorded endpoint, as strings for the channel metadata.
struct QosDescription {
  std::string reliability;  // "RELIABLE" | "BEST_EFFORT"
  std::string durability;   // "VOLATILE" | "TRANSIENT_LOCAL" | ...
  std::string history;      // "KEEP_LAST" | "KEEP_ALL"
  int depth = 0;
};

// Channel metadata: topic, type, the delivery mode the chain used (lossless/live, which the
// replayer uses to choose writer profiles) and the QoS the recorder subscribed with.
mcap::KeyValueMap channel_metadata(const TopicSpec& spec, dds::DeliveryMode mode, const QosDescription& qos);

// The delivery mode a recording's channel asks for: its "mode" metadata, else `fallback`.
dds::DeliveryMode recorded_mode(const mcap::Channel& channel, dds::DeliveryMode fallback);

}  // namespace uavmot::record
