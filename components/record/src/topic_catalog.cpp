#include "uavmot/record/topic_catalog.hpp"

#include <fnmatch.h>

#include <cstdlib>
#include <filesystem>

#include "uavmot/build_paths/build_paths.hpp"
#include "uavmot/core/error.hpp"
#include "uavmot/mcap/idl_schema.hpp"

namespace uavmot::record {
namespace fs = std::filesystem;

const std::vector<TopicSpec>& uavmot_topics() {
  static const std::vector<TopicSpec> topics = {
      {dds::kFramesTopic, "uavmot::msg::Frame", "frame.idl", dds::TopicClass::Frames},
      {dds::kMotionTopic, "uavmot::msg::MotionEstimate", "motion.idl", dds::TopicClass::Chain},
      {dds::kSegmentationTopic, "uavmot::msg::Segmentation", "segmentation.idl", dds::TopicClass::Chain},
      {dds::kTracksTopic, "uavmot::msg::TrackList", "tracks.idl", dds::TopicClass::Chain},
      {dds::kHealthTopic, "uavmot::msg::ComponentHealth", "health.idl", dds::TopicClass::Health},
  };
  return topics;
}

const TopicSpec* find_topic(const std::string& topic) {
  for (const auto& spec : uavmot_topics()) {
    if (spec.topic == topic) return &spec;
  }
  return nullptr;
}

bool matches_any(const std::string& name, const std::vector<std::string>& patterns) {
  for (const auto& pattern : patterns) {
    if (::fnmatch(pattern.c_str(), name.c_str(), 0) == 0) return true;
  }
  return false;
}

bool is_selected(const std::string& name, const std::vector<std::string>& include, const std::vector<std::string>& exclude) {
  return (include.empty() || matches_any(name, include)) && !matches_any(name, exclude);
}

std::vector<TopicSpec> select_topics(const std::vector<std::string>& include, const std::vector<std::string>& exclude) {
  for (const auto& pattern : include) {
    bool any = false;
    for (const auto& spec : uavmot_topics()) any = any || matches_any(spec.topic, {pattern});
    if (!any) {
      std::string names;
      for (const auto& spec : uavmot_topics()) names += (names.empty() ? "" : ", ") + spec.topic;
      throw InputError("--topics '" + pattern + "' matches no uavmot topic (known: " + names + ")");
    }
  }
  std::vector<TopicSpec> chosen;
  for (const auto& spec : uavmot_topics()) {
    if (is_selected(spec.topic, include, exclude)) chosen.push_back(spec);
  }
  if (chosen.empty()) throw InputError("--topics/--exclude leave no topic to record");
  return chosen;
}

namespace {
fs::path executable_dir() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  return ec ? fs::path() : exe.parent_path();
}
}  // namespace

std::string find_idl_dir() {
  std::vector<fs::path> candidates;
  if (const char* env = std::getenv("UAVMOT_IDL_DIR"); env && *env) candidates.emplace_back(env);
  candidates.push_back(executable_dir() / ".." / "share" / "uavmot" / "idl");
  candidates.push_back(fs::path(build_paths::source_dir()) / "idl");  // the build tree's binaries
  std::string tried;
  for (const auto& dir : candidates) {
    if (fs::is_regular_file(dir / "frame.idl")) return fs::weakly_canonical(dir).string();
    tried += (tried.empty() ? "" : ", ") + dir.string();
  }
  throw InputError("cannot find the uavmot IDL files (tried " + tried + "); set UAVMOT_IDL_DIR");
}

std::string schema_text(const TopicSpec& spec, const std::string& idl_dir) {
  return mcap::flatten_idl((fs::path(idl_dir) / spec.idl_file).string());
}

mcap::KeyValueMap channel_metadata(const TopicSpec& spec, dds::DeliveryMode mode, const QosDescription& qos) {
  return {{"topic", spec.topic},
          {"type", spec.type_name},
          {"mode", spec.topic_class == dds::TopicClass::Health ? "health" : dds::to_string(mode)},
          {"reliability", qos.reliability},
          {"durability", qos.durability},
          {"history", qos.history},
          {"depth", std::to_string(qos.depth)}};
}

dds::DeliveryMode recorded_mode(const mcap::Channel& channel, dds::DeliveryMode fallback) {
  const auto it = channel.metadata.find("mode");
  if (it == channel.metadata.end()) return fallback;
  if (it->second == "lossless") return dds::DeliveryMode::Lossless;
  if (it->second == "live") return dds::DeliveryMode::Live;
  return fallback;
}

}  // namespace uavmot::record
