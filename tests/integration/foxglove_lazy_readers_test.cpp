// `uavmot foxglove` stays out of the chain's way. It reads a chain topic only while a viewer
// watches it: with no viewer the chain's writers see no bridge reader at all (nothing extra to
// serialise or send), a viewer subscribing to a topic's channel brings the reader, and the reader
// goes when the last viewer of that topic leaves. The chain is played by this test's own writer on
// `uavmot/tracks` (live mode: the bridge subscribes without waiting for the writer's health). And
// by default each of its threads runs at idle CPU priority.

#include <sched.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "child_process.hpp"
#include "tracksPubSubTypes.h"
#include "uavmot/dds/participant.hpp"
#include "ws_test_client.hpp"

namespace uavmot {
namespace {
using json = nlohmann::json;
using testing::binary;
using testing::ChildProcess;
constexpr int kDomain = 83;

// The port the bridge printed ("serving ... on ws://127.0.0.1:PORT").
uint16_t served_port(const ChildProcess& bridge) {
  std::smatch m;
  for (int i = 0; i < 300; ++i) {
    const std::string log = bridge.log();
    if (std::regex_search(log, m, std::regex(R"(ws://127\.0\.0\.1:(\d+))"))) return static_cast<uint16_t>(std::stoi(m[1]));
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  return 0;
}

// The advertised channel id of `topic`.
uint32_t channel_id(foxglove::TestClient& viewer, const std::string& topic) {
  EXPECT_EQ(viewer.receive_json()["op"], "serverInfo");
  const json advertise = viewer.receive_json();
  EXPECT_EQ(advertise["op"], "advertise");
  for (const auto& channel : advertise["channels"]) {
    if (channel["topic"] == topic) return channel["id"].get<uint32_t>();
  }
  ADD_FAILURE() << topic << " not advertised: " << advertise.dump();
  return 0;
}

TEST(FoxgloveBridge, ReadsATopicOnlyWhileAViewerWatchesIt) {
  const std::string dir = testing::fresh_dir("foxglove_lazy_readers");
  // Normal priority: at the default (idle) a bridge beside a busy test on the same cores could wait
  // seconds for its turn, and this test is about readers, not priority.
  ChildProcess bridge({binary("uavmot-foxglove"), "--port", "0", "--domain", std::to_string(kDomain), "--mode", "live",
                       "--topics", "uavmot/tracks", "--cpu-priority", "normal"},
                      dir + "/bridge.log");
  const uint16_t port = served_port(bridge);
  ASSERT_NE(port, 0) << bridge.log();

  dds::DdsOptions options;
  options.domain_id = kDomain;
  options.mode = dds::DeliveryMode::Live;
  options.participant_name = "chain";
  dds::Participant chain(options);
  auto writer = chain.make_writer<msg::TrackListPubSubType>(dds::kTracksTopic, dds::TopicClass::Chain);

  // Discovery between two processes on one host takes well under a second; 2 s without a match
  // means the bridge has no reader.
  std::this_thread::sleep_for(std::chrono::seconds(2));
  EXPECT_EQ(writer->matched(), 0) << "a bridge without viewers reads the chain's topic";

  {
    foxglove::TestClient viewer(port);
    const uint32_t tracks = channel_id(viewer, "uavmot/tracks");
    std::this_thread::sleep_for(std::chrono::seconds(1));
    EXPECT_EQ(writer->matched(), 0) << "a connected viewer that watches nothing brought a reader";

    viewer.send_text(json{{"op", "subscribe"}, {"subscriptions", {{{"id", 1}, {"channelId", tracks}}}}}.dump());
    ASSERT_TRUE(writer->wait_for_matched(1, std::chrono::seconds(10))) << bridge.log();

    // The viewer gets what the chain writes.
    msg::TrackList list;
    list.stream_id("s");
    list.frame_index(7);
    bool received = false;
    for (int i = 0; i < 5 && !received; ++i) {  // the first samples may beat discovery
      writer->write(list);
      try {
        const auto [opcode, payload] = viewer.receive();
        received = opcode == 2 && !payload.empty() && static_cast<uint8_t>(payload[0]) == 1;  // binary messageData
      } catch (const std::exception&) {
      }
    }
    EXPECT_TRUE(received) << "the subscribed viewer got no message";

    viewer.send_text(json{{"op", "unsubscribe"}, {"subscriptionIds", {1}}}.dump());
    EXPECT_TRUE(foxglove::eventually([&] { return writer->matched() == 0; }))
        << "the reader stayed after the only viewer unsubscribed";

    viewer.send_text(json{{"op", "subscribe"}, {"subscriptions", {{{"id", 2}, {"channelId", tracks}}}}}.dump());
    ASSERT_TRUE(writer->wait_for_matched(1, std::chrono::seconds(10))) << "no reader for a second subscription";
  }
  // The viewer's connection closed: its subscriptions end with it.
  EXPECT_TRUE(foxglove::eventually([&] { return writer->matched() == 0; })) << "the reader stayed after the viewer left";

  bridge.signal(SIGTERM);
  EXPECT_EQ(bridge.wait(std::chrono::seconds(20)), 0) << bridge.log();
}

// The scheduling policy of every thread of process `pid` (field 41 of /proc/PID/task/TID/stat).
std::vector<int> thread_policies(pid_t pid) {
  std::vector<int> policies;
  for (const auto& task : std::filesystem::directory_iterator("/proc/" + std::to_string(pid) + "/task")) {
    std::ifstream in(task.path() / "stat");
    std::string stat((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    // After the command name's closing parenthesis, fields start at 3 (state).
    std::istringstream fields(stat.substr(stat.rfind(')') + 2));
    std::string field;
    for (int i = 3; i <= 41 && fields >> field; ++i) {
      if (i == 41) policies.push_back(std::stoi(field));
    }
  }
  return policies;
}

// By default the bridge runs only on CPU time the chain leaves: SCHED_IDLE on every thread, those
// Fast DDS and the WebSocket server start included (the cost of viewers is the bridge's, never the chain's).
TEST(FoxgloveBridge, EveryThreadRunsAtIdlePriorityByDefault) {
  const std::string dir = testing::fresh_dir("foxglove_idle_priority");
  ChildProcess bridge({binary("uavmot-foxglove"), "--port", "0", "--domain", std::to_string(kDomain), "--mode", "live",
                       "--topics", "uavmot/tracks", "--duration", "30"},
                      dir + "/bridge.log");
  ASSERT_NE(served_port(bridge), 0) << bridge.log();
  const auto policies = thread_policies(bridge.pid());
  EXPECT_GE(policies.size(), 3u) << "the main thread, Fast DDS's and the server's";
  for (const int policy : policies) EXPECT_EQ(policy, SCHED_IDLE) << bridge.log();
  EXPECT_NE(bridge.log().find("CPU priority idle"), std::string::npos) << bridge.log();
  bridge.signal(SIGTERM);
  EXPECT_EQ(bridge.wait(std::chrono::seconds(20)), 0) << bridge.log();
}

}  // namespace
}  // namespace uavmot
