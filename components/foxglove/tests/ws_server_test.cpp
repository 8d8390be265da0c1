// The Foxglove WebSocket server, spoken to over a real TCP socket by the minimal client of
// ws_test_client.hpp: what it advertises, what it sends a subscriber, that a viewer who stops
// reading loses messages while publish() goes on at full speed, and the errors for a port in use or
// a bad address.

#include <gtest/gtest.h>

#include <chrono>
#include <thread>
#include <cstring>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "uavmot/core/error.hpp"
#include "uavmot/foxglove/ws_server.hpp"
#include "ws_test_client.hpp"

namespace uavmot::foxglove {
namespace {
using json = nlohmann::json;

WsChannel channel(const std::string& topic) { return {topic, "cdr", "foxglove::ImageAnnotations", "struct X {};", "omgidl"}; }

TEST(WsServer, AdvertisesChannelsAndSendsSubscribedMessages) {
  WsServer server({.address = "127.0.0.1", .port = 0});
  const uint32_t tracks = server.add_channel(channel("uavmot/foxglove/tracks"));
  const uint32_t image = server.add_channel(channel("uavmot/foxglove/image"));
  TestClient client(server.port());
  EXPECT_NE(client.handshake().find(" 101 "), std::string::npos) << client.handshake();
  EXPECT_NE(client.handshake().find("Sec-WebSocket-Protocol: foxglove.websocket.v1"), std::string::npos);

  const json info = client.receive_json();
  EXPECT_EQ(info["op"], "serverInfo");
  EXPECT_EQ(info["name"], "uavmot");
  const json advertise = client.receive_json();
  ASSERT_EQ(advertise["op"], "advertise");
  ASSERT_EQ(advertise["channels"].size(), 2u);
  EXPECT_EQ(advertise["channels"][0]["id"], tracks);
  EXPECT_EQ(advertise["channels"][0]["topic"], "uavmot/foxglove/tracks");
  EXPECT_EQ(advertise["channels"][0]["schemaEncoding"], "omgidl");
  EXPECT_EQ(advertise["channels"][0]["schemaName"], "foxglove::ImageAnnotations");

  EXPECT_FALSE(server.has_subscribers(tracks));
  client.send_text(json{{"op", "subscribe"}, {"subscriptions", {{{"id", 42}, {"channelId", tracks}}}}}.dump());
  ASSERT_TRUE(eventually([&] { return server.has_subscribers(tracks); }));
  EXPECT_FALSE(server.has_subscribers(image));
  const std::vector<uint8_t> payload = {0, 1, 0, 0, 9, 8, 7};
  server.publish(image, 5, payload.data(), payload.size());  // nobody subscribed: not sent
  server.publish(tracks, 0x0102030405060708ull, payload.data(), payload.size());
  const auto [opcode, message] = client.receive();
  ASSERT_EQ(opcode, 2);  // binary
  ASSERT_EQ(message.size(), 13u + payload.size());
  EXPECT_EQ(message[0], 1);  // MESSAGE_DATA
  uint32_t subscription;
  uint64_t timestamp;
  std::memcpy(&subscription, message.data() + 1, 4);
  std::memcpy(&timestamp, message.data() + 5, 8);
  EXPECT_EQ(subscription, 42u);
  EXPECT_EQ(timestamp, 0x0102030405060708ull);
  EXPECT_EQ(std::string(message.data() + 13, payload.size()), std::string(payload.begin(), payload.end()));

  // A channel added later is advertised to clients already connected.
  server.add_channel(channel("uavmot/health"));
  const json later = client.receive_json();
  EXPECT_EQ(later["op"], "advertise");
  EXPECT_EQ(later["channels"][0]["topic"], "uavmot/health");

  client.send_text(R"({"op": "subscribe", "subscriptions": [{"id": 1, "channelId": 99}]})");
  const json status = client.receive_json();
  EXPECT_EQ(status["op"], "status");
  EXPECT_EQ(status["level"], 2);
  client.send_text(json{{"op", "unsubscribe"}, {"subscriptionIds", {42}}}.dump());
  ASSERT_TRUE(eventually([&] { return !server.has_subscribers(tracks); }));
  EXPECT_EQ(server.counts().messages_sent, 1u);
  EXPECT_EQ(server.counts().clients, 1u);
}

TEST(WsServer, RefusesClientsWithoutTheFoxgloveSubprotocol) {
  WsServer server({.address = "127.0.0.1", .port = 0});
  TestClient client(server.port(), "");
  EXPECT_EQ(client.handshake().find(" 101 "), std::string::npos) << client.handshake();
  EXPECT_EQ(server.counts().clients_seen, 0u);
}

TEST(WsServer, ASlowViewerLosesMessagesAndNeverSlowsPublish) {
  const size_t buffer = 1u << 20;
  WsServer server({.address = "127.0.0.1", .port = 0, .client_buffer_bytes = buffer});
  const uint32_t image = server.add_channel(channel("uavmot/foxglove/image"));
  TestClient slow(server.port(), "foxglove.websocket.v1", 4096);  // reads nothing after subscribing
  slow.receive_json();
  slow.receive_json();
  slow.send_text(json{{"op", "subscribe"}, {"subscriptions", {{{"id", 0}, {"channelId", image}}}}}.dump());
  ASSERT_TRUE(eventually([&] { return server.has_subscribers(image); }));

  const std::vector<uint8_t> frame(256 * 1024, 0x55);
  const int frames = 400;  // 100 MiB: far more than the socket and the 1 MiB queue hold
  const auto start = std::chrono::steady_clock::now();
  for (int i = 0; i < frames; ++i) server.publish(image, static_cast<uint64_t>(i), frame.data(), frame.size());
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const auto counts = server.counts();
  EXPECT_GT(counts.messages_dropped, static_cast<uint64_t>(frames / 2));
  EXPECT_LE(counts.messages_sent + counts.messages_dropped, static_cast<uint64_t>(frames));  // the rest still queued
  // 400 x 256 KiB copied once each: milliseconds (2 s under TSan on a loaded machine); waiting for
  // the viewer, who never reads, would never end.
  EXPECT_LT(seconds, 10.0);
}

TEST(WsServer, PortInUseAndBadAddressAreClearErrors) {
  WsServer first({.address = "127.0.0.1", .port = 0});
  const uint16_t port = first.port();
  try {
    WsServer second({.address = "127.0.0.1", .port = port});
    FAIL() << "a second server on port " << port << " started";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("cannot listen on 127.0.0.1:" + std::to_string(port)), std::string::npos) << message;
    EXPECT_NE(message.find("in use"), std::string::npos) << message;
  }
  EXPECT_THROW(WsServer({.address = "localhost:80", .port = 0}), InputError);
}

}  // namespace
}  // namespace uavmot::foxglove
