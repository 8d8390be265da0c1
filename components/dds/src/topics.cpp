#include "uavmot/dds/topics.hpp"

#include "uavmot/core/error.hpp"

namespace uavmot::dds {
namespace {
std::string profile(TopicClass topic_class, DeliveryMode mode, const char* side) {
  switch (topic_class) {
    case TopicClass::Frames: return std::string("frames_") + to_string(mode) + "_" + side;
    case TopicClass::Chain: return std::string("chain_") + to_string(mode) + "_" + side;
    case TopicClass::FramesResume:
      if (mode == DeliveryMode::Lossless && std::string(side) == "reader") return "frames_lossless_resume_reader";
      return std::string("frames_") + to_string(mode) + "_" + side;
    case TopicClass::ChainResume:
      if (mode == DeliveryMode::Lossless && std::string(side) == "reader") return "chain_lossless_resume_reader";
      return std::string("chain_") + to_string(mode) + "_" + side;
    case TopicClass::Downlink: return std::string("downlink_") + to_string(mode) + "_" + side;
    case TopicClass::Preview: return std::string("preview_") + side;
    case TopicClass::Health: return std::string("health_") + side;
    case TopicClass::State: return std::string("state_") + side;
  }
  return "";
}
}  // namespace

DeliveryMode parse_delivery_mode(const std::string& name) {
  if (name == "lossless") return DeliveryMode::Lossless;
  if (name == "live") return DeliveryMode::Live;
  throw InvalidArgument("unknown delivery mode '" + name + "' (expected lossless or live)");
}

const char* to_string(DeliveryMode mode) { return mode == DeliveryMode::Lossless ? "lossless" : "live"; }

std::string writer_profile(TopicClass topic_class, DeliveryMode mode) { return profile(topic_class, mode, "writer"); }
std::string reader_profile(TopicClass topic_class, DeliveryMode mode) { return profile(topic_class, mode, "reader"); }

}  // namespace uavmot::dds
