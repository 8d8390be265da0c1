#include "uavmot/record/topic_catalog.hpp"

#include <gtest/gtest.h>

#include "uavmot/core/error.hpp"

namespace uavmot::record {
namespace {

std::vector<std::string> names(const std::vector<TopicSpec>& specs) {
  std::vector<std::string> out;
  for (const auto& s : specs) out.push_back(s.topic);
  return out;
}

TEST(TopicSelection, EveryTopicByDefaultInChainOrder) {
  EXPECT_EQ(names(select_topics({}, {})),
            (std::vector<std::string>{"uavmot/frames", "uavmot/motion", "uavmot/segmentation", "uavmot/tracks",
                                      "uavmot/health"}));
  EXPECT_EQ(select_topics({"uavmot/*"}, {}).size(), 5u);
}

TEST(TopicSelection, WildcardsIncludeAndExclude) {
  EXPECT_EQ(names(select_topics({"uavmot/motion", "*/seg*"}, {})),
            (std::vector<std::string>{"uavmot/motion", "uavmot/segmentation"}));
  EXPECT_EQ(names(select_topics({}, {"uavmot/frames", "*health"})),
            (std::vector<std::string>{"uavmot/motion", "uavmot/segmentation", "uavmot/tracks"}));
  EXPECT_EQ(names(select_topics({"uavmot/[mt]*"}, {"*/tracks"})), (std::vector<std::string>{"uavmot/motion"}));
  EXPECT_TRUE(matches_any("uavmot/tracks", {"uavmot/t?acks"}));
  EXPECT_FALSE(matches_any("uavmot/tracks", {"tracks"}));
  EXPECT_TRUE(is_selected("x/y", {}, {}));
  EXPECT_FALSE(is_selected("uavmot/frames", {"uavmot/*"}, {"*frames"}));
}

TEST(TopicSelection, PatternMatchingNothingIsNamed) {
  try {
    select_topics({"uavmot/track"}, {});
    FAIL() << "a pattern matching no topic must be an error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("'uavmot/track'"), std::string::npos) << e.what();
  }
  EXPECT_THROW(select_topics({"uavmot/motion"}, {"uavmot/*"}), InputError);
}

TEST(Schema, SelfContainedIdlDefiningTheNamedType) {
  const std::string dir = find_idl_dir();
  for (const auto& spec : uavmot_topics()) {
    const std::string text = schema_text(spec, dir);
    EXPECT_EQ(text.find("#include"), std::string::npos) << spec.topic;
    // "uavmot::msg::TrackList" is defined as struct TrackList inside modules uavmot and msg.
    const std::string leaf = spec.type_name.substr(spec.type_name.rfind(':') + 1);
    EXPECT_NE(text.find("struct " + leaf + " {"), std::string::npos) << spec.topic;
    EXPECT_EQ(spec.type_name.rfind("uavmot::msg::", 0), 0u);
  }
  // tracks.idl includes common.idl: OrientedBox must be inlined.
  EXPECT_NE(schema_text(*find_topic("uavmot/tracks"), dir).find("struct OrientedBox"), std::string::npos);
  EXPECT_EQ(find_topic("uavmot/nothing"), nullptr);
}

TEST(ChannelMetadata, TopicTypeModeAndQos) {
  const auto md = channel_metadata(*find_topic("uavmot/motion"), dds::DeliveryMode::Lossless,
                                   {"RELIABLE", "VOLATILE", "KEEP_ALL", 0});
  EXPECT_EQ(md.at("topic"), "uavmot/motion");
  EXPECT_EQ(md.at("type"), "uavmot::msg::MotionEstimate");
  EXPECT_EQ(md.at("mode"), "lossless");
  EXPECT_EQ(md.at("reliability"), "RELIABLE");
  EXPECT_EQ(md.at("durability"), "VOLATILE");
  EXPECT_EQ(md.at("history"), "KEEP_ALL");
  EXPECT_EQ(md.at("depth"), "0");

  mcap::Channel channel;
  channel.metadata = channel_metadata(*find_topic("uavmot/frames"), dds::DeliveryMode::Live, {});
  EXPECT_EQ(recorded_mode(channel, dds::DeliveryMode::Lossless), dds::DeliveryMode::Live);
  channel.metadata.clear();  // another recorder's file: the fallback
  EXPECT_EQ(recorded_mode(channel, dds::DeliveryMode::Lossless), dds::DeliveryMode::Lossless);
}

}  // namespace
}  // namespace uavmot::record
